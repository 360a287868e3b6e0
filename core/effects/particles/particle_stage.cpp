#include "core/effects/particles/particle_stage.h"

#include <algorithm>
#include <cmath>

#include "core/effects/particles/particle_buffers.h"
#include "core/effects/particles/particle_model.h"
#include "core/effects/surface/surface_stage.h"

namespace bleedsim {
namespace {

constexpr std::size_t kInitialEmitters = 16;

int substeps_of(const Scene& scene) {
  return particle_mechanics(*scene.particles, scene.domain, scene.frame_rate_hz).substeps;
}

// A frame's step list and its emitters (room at first for every cut, or 16, bleeding every step).
std::size_t plan_bytes(const Scene& scene) {
  const std::size_t emitters = std::max(kInitialEmitters, scene.cuts.size());
  return std::size_t(substeps_of(scene)) * (sizeof(ParticleStep) + emitters * sizeof(Emitter));
}

// The CUDA bin's counts per cell, two words per slot and the scan's storage; this bounds it.
std::size_t sort_scratch_bound(std::size_t capacity, std::size_t cells) {
  return (2 * capacity + cells + 1) * sizeof(std::uint32_t) + (1u << 20);
}

// emitted, alive, expired, overwritten; and aspirated in a scene with suction.
int accounting_elements(const Scene& scene) { return scene.suction ? 5 : 4; }

// Particles a cut has emitted by time t: the blood its wound has given over the part of
// [start, start + bleed] before t, a whole particle at a time.
std::uint64_t emitted_by(const Cut& cut, const Scene& scene, double t) {
  const double blood = cut_blood_mm3(cut, t, scene.pulse ? &*scene.pulse : nullptr);
  return std::uint64_t(std::floor(blood / scene.particles->particle_volume_mm3));
}

}  // namespace

ParticleStage::ParticleStage(const StageKind& kind, const Scene& scene, State& state, Backend& backend)
    : Stage(kind),
      accounting_(std::uint64_t(scene.particles->capacity), particle_lifetime(scene).steps),
      substeps_(substeps_of(scene)) {
  const int capacity = scene.particles->capacity;
  args_.model = make_particle_model(scene);
  args_.model.surface = surface_map(scene, state);
  const ParticleModel& model = args_.model;
  ParticleArrays& a = args_.arrays;
  a.capacity = capacity;
  Field& position = add_field(scene, state, backend, "particles/position", capacity);
  Field& velocity = add_field(scene, state, backend, "particles/velocity", capacity);
  Field& age = add_field(scene, state, backend, "particles/age", capacity);
  counts_ = &add_field(scene, state, backend, "particles/accounting", accounting_elements(scene));
  a.position = position.data.as<float>();
  a.velocity = velocity.data.as<float>();
  a.age = age.data.as<std::uint32_t>();

  const std::size_t sort_bytes = backend.particle_sort_scratch_bytes(capacity, cell_count(model));
  scratch_ = allocate(backend, particle_scratch_bytes(cell_count(model), capacity, sort_bytes));
  point_particle_scratch(a, cell_count(model), scratch_.data(), sort_bytes);
  plan_ = allocate(backend, plan_bytes(scene));

  clear_particles(backend, a);
  if (scene.suction || scene.contact) instrument_.emplace(scene, backend, capacity);
  const ParticleCounts none{};
  backend.upload(counts_->data.data(), &none, counts_->bytes());
}

MemoryParts ParticleStage::memory_for(const Scene& scene) {
  const ParticleParams& p = *scene.particles;
  const std::size_t n = std::size_t(p.capacity);
  const std::size_t fields = n * (2 * sizeof(float) + 2 * sizeof(float) + sizeof(std::uint32_t)) +
                             sizeof(ParticleCounts);
  // The scratch is per slot and per grid cell: its grid part is what the cells add to it. The cell
  // count is below kMaxGridCells once the scene's checks have passed.
  const std::size_t cells = particle_cell_count(scene).to<std::size_t>();
  const std::size_t per_slot = particle_scratch_bytes(0, p.capacity, sort_scratch_bound(n, 0));
  const std::size_t with_grid = particle_scratch_bytes(cells, p.capacity, sort_scratch_bound(n, cells));
  MemoryParts parts{
      {"particles.capacity", std::to_string(p.capacity) + " particle slots", Count(fields) + per_slot},
      {p.cell_mm > 0 ? "particles.cell_mm" : "particles.diameter_mm",
       "a collision grid of " + std::to_string(particle_cell_count(scene).value()) + " cells", with_grid - per_slot},
      {"cut", "a frame's steps and the particles' emitters", Count(plan_bytes(scene))}};
  for (const MemoryPart& part : Instrument::memory_for(scene)) parts.push_back(part);
  return parts;
}

// Plans `step`'s emission: the particles each cut has given since the step before, appended to the
// frame's emitters, and the accounting told of them.
void ParticleStage::plan_emission(const Scene& scene, const State& state, std::uint64_t step, ParticleStep& planned) {
  const double steps_per_s = particle_steps_per_s(scene);
  const double t0 = double(step) / steps_per_s, t1 = double(step + 1) / steps_per_s;
  const std::uint64_t capacity = std::uint64_t(args_.arrays.capacity);
  const PulseParams* pulse = scene.pulse ? &*scene.pulse : nullptr;
  const std::size_t first = emitters_.size();
  std::uint64_t id = accounting_.counts().emitted, total = 0;
  for (const Cut& cut : state.cuts) {
    // The cumulative blood never falls, but its rounding could by an ulp where a beat's flow is
    // least: such a dip emits nothing rather than wrapping the unsigned count.
    const std::uint64_t before = emitted_by(cut, scene, t0), by_end = emitted_by(cut, scene, t1);
    const std::uint64_t count = by_end > before ? by_end - before : 0;
    if (count == 0) continue;
    // first_new is set once the step's total is known (below).
    emitters_.push_back({float(cut.x_mm), float(cut.y_mm), id, 0u, std::uint32_t(count),
                         float(cut_exit_speed_scale(cut, (t0 + t1) / 2.0, pulse))});
    id += count;
    total += count;
  }
  accounting_.emit(step, total);
  // More new particles than slots: only the newest `capacity` are written; the older ones are
  // overwritten in the same step (the accounting has counted them so).
  std::uint64_t skip = total > capacity ? total - capacity : 0, first_new = 0;
  std::size_t kept = first;
  for (std::size_t k = first; k < emitters_.size(); ++k) {
    Emitter e = emitters_[k];
    const std::uint64_t dropped = std::min<std::uint64_t>(skip, e.count);
    skip -= dropped;
    if (dropped == e.count) continue;
    e.first_id += dropped;
    e.count -= std::uint32_t(dropped);
    e.first_new = std::uint32_t(first_new);
    first_new += e.count;
    emitters_[kept++] = e;
  }
  emitters_.resize(kept);
  planned.step = step;
  planned.first_emitter = std::uint32_t(first);
  planned.emitter_count = int(kept - first);
  planned.new_count = int(first_new);
}

// The live particles, ids [oldest alive, emitted), from the accounting.
void ParticleStage::live_range(std::uint32_t& first_live_slot, int& live_count) const {
  live_count = int(accounting_.counts().alive);
  first_live_slot = std::uint32_t(accounting_.oldest_alive() % std::uint64_t(args_.arrays.capacity));
}

void ParticleStage::plan_frame(const Scene& scene, const State& state, Backend& backend) {
  steps_.assign(std::size_t(substeps_), ParticleStep{});
  emitters_.clear();
  for (int s = 0; s < substeps_; ++s) {
    ParticleStep& planned = steps_[std::size_t(s)];
    const std::uint64_t step = std::uint64_t(state.frames_done) * std::uint64_t(substeps_) + std::uint64_t(s);
    live_range(planned.emit_first_live_slot, planned.emit_live_count);
    plan_emission(scene, state, step, planned);
    live_range(planned.first_live_slot, planned.live_count);
    accounting_.end_step(step);
  }
  // The device's copy of the plan grows with the busiest frame's emitters.
  const std::size_t bytes = steps_.size() * sizeof(ParticleStep) + emitters_.size() * sizeof(Emitter);
  if (bytes > plan_.bytes()) plan_ = allocate(backend, 2 * bytes);
}

void ParticleStage::run(const Scene& scene, State& state, Backend& backend) {
  plan_frame(scene, state, backend);
  ParticleStep* device_steps = plan_.as<ParticleStep>();
  Emitter* device_emitters = reinterpret_cast<Emitter*>(device_steps + steps_.size());
  // The instrument acts between one step's integrate and the next step: with one, a run is a step.
  const int run_steps = instrument_ ? 1 : substeps_;
  const double steps_per_s = particle_steps_per_s(scene);
  for (int s = 0; s < substeps_; s += run_steps) {
    launch(backend, ParticleSteps{args_, &steps_[std::size_t(s)], run_steps, emitters_.data(), int(emitters_.size()),
                                  device_steps + s, device_emitters, &graph_});
    if (!instrument_) continue;
    const ParticleStep& step = steps_[std::size_t(s)];
    instrument_->act(scene, state, backend, args_at(args_, step, device_emitters, ParticlePhase::integrate),
                     double(step.step) / steps_per_s, double(step.step + 1) / steps_per_s);
  }
  ParticleCounts counts = accounting_.counts();
  if (scene.suction) {
    AspiratedFates fates;
    backend.download(&fates, args_.arrays.fates, sizeof fates);
    counts = with_aspirated(counts, fates);
  }
  backend.upload(counts_->data.data(), &counts, counts_->bytes());
}

}  // namespace bleedsim
