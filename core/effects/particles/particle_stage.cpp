// The particle effect: its stage, and its row (declared in particle_params.h) with the splat's stage.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <memory>
#include <vector>

#include "core/bleeding/cut_flow.h"
#include "core/bleeding/heartbeat.h"
#include "core/effects/effect.h"
#include "core/effects/particle_hook.h"
#include "core/effects/particles/particle_accounting.h"
#include "core/effects/particles/particle_buffers.h"
#include "core/effects/particles/particle_model.h"
#include "core/effects/particles/splat_stage.h"
#include "core/effects/pulse/pulse_params.h"
#include "core/effects/stage.h"
#include "core/effects/suction/suction_params.h"
#include "core/effects/surface/surface_stage.h"
#include "core/physics/particles.h"
#include "core/runtime/message_text.h"

namespace bleedsim {

// (cuts, instrument, particles/position, velocity, age) => particles/position, velocity, age, accounting
// Each frame: `substeps` physics steps (emit, bin, collide, integrate, and after each the hooks of
// the effects the scene declares: the suction, the tip's contact), then the accounting recorded.
// The ring buffer's state is in fields, so it is hashed, compared and written like any other output.
class ParticleStage final : public Stage {
 public:
  ParticleStage(const StageKind& kind, const Scene& scene, const Resolved& resolved, State& state, Backend& backend);
  // An upper bound: the CUDA sort's scratch depends on the device.
  static MemoryParts memory_for(const Scene& scene, const Resolved& resolved);
  void run(const Scene& scene, State& state, Backend& backend) override;

 private:
  // Every step of this frame planned on the host (emission, live ranges, accounting), before any runs.
  void plan_frame(const State& state, Backend& backend);
  void plan_emission(const State& state, std::uint64_t step, ParticleStep& planned);
  void live_range(std::uint32_t& first_live_slot, int& live_count) const;

  ParticleArgs args_{};      // the model and arrays; a step's own arguments are in steps_
  Field* counts_ = nullptr;  // the accounting, uploaded each frame (aspirated only with [suction])
  ParticleAccounting accounting_;
  int substeps_;                                      // physics steps per frame
  double steps_per_s_;                                // ... and per second
  double particle_volume_mm3_;                        // the blood one particle stands for
  const Heartbeat* beat_;                             // the scene's, with [pulse]; else null
  Buffer scratch_;                                    // every array of ParticleArrays that is not a field
  std::vector<ParticleStep> steps_;                   // this frame's
  std::vector<Emitter> emitters_;                     // this frame's steps' emitters, in step order
  Buffer plan_;                                       // the backend's copy of both; grows with the emitters
  std::unique_ptr<TwinCache> graph_;                  // the backend's (CUDA: the steps' graph)
  std::vector<std::unique_ptr<ParticleHook>> hooks_;  // the scene's effects', in the list's order
};
namespace {

constexpr std::size_t kInitialEmitters = 16;

const ParticleSettings& settings_of(const Resolved& resolved) { return resolved.get<ParticleSettings>(); }

// A frame's step list and its emitters (room at first for every cut, or 16, bleeding every step).
std::size_t plan_bytes(const Scene& scene, const Resolved& resolved) {
  const std::size_t emitters = std::max(kInitialEmitters, scene.cuts.size());
  return std::size_t(settings_of(resolved).mechanics.substeps) * (sizeof(ParticleStep) + emitters * sizeof(Emitter));
}

// The CUDA bin's counts per cell, two words per slot and the scan's storage; this bounds it.
std::size_t sort_scratch_bound(std::size_t capacity, std::size_t cells) {
  return (2 * capacity + cells + 1) * sizeof(std::uint32_t) + (1u << 20);
}

// emitted, alive, expired, overwritten; and aspirated in a scene with suction.
int accounting_elements(const Scene& scene) { return scene.effects.has<SuctionParams>() ? 5 : 4; }

// Particles a cut has emitted by time t: the blood its wound has given over the part of
// [start, start + bleed] before t, a whole particle at a time.
std::uint64_t emitted_by(const Cut& cut, const Heartbeat* beat, double particle_volume_mm3, double t) {
  return std::uint64_t(std::floor(cut_blood_mm3(cut, t, beat) / particle_volume_mm3));
}

}  // namespace

ParticleStage::ParticleStage(const StageKind& kind, const Scene& scene, const Resolved& resolved, State& state,
                             Backend& backend)
    : Stage(kind),
      accounting_(std::uint64_t(scene.effects.get<ParticleParams>().capacity), settings_of(resolved).lifetime.steps),
      substeps_(settings_of(resolved).mechanics.substeps),
      steps_per_s_(settings_of(resolved).steps_per_s),
      particle_volume_mm3_(scene.effects.get<ParticleParams>().particle_volume_mm3),
      beat_(scene.effects.find<PulseParams>()) {
  const int capacity = scene.effects.get<ParticleParams>().capacity;
  args_.model = settings_of(resolved).model;
  args_.model.surface = surface_map(scene, state);
  const ParticleModel& model = args_.model;
  ParticleArrays& a = args_.arrays;
  a.capacity = capacity;
  Field& position = add_field(scene, state, backend, "particles/position", capacity);
  Field& velocity = add_field(scene, state, backend, "particles/velocity", capacity);
  Field& age = add_field(scene, state, backend, "particles/age", capacity);
  Field& rest = add_field(scene, state, backend, "particles/rest", capacity);
  Field& anchor = add_field(scene, state, backend, "particles/anchor", capacity);
  counts_ = &add_field(scene, state, backend, "particles/accounting", accounting_elements(scene));
  a.position = position.data.as<float>();
  a.velocity = velocity.data.as<float>();
  a.age = age.data.as<std::uint32_t>();
  a.rest = rest.data.as<std::uint32_t>();
  a.anchor = anchor.data.as<float>();

  const std::size_t sort_bytes = backend.particle_sort_scratch_bytes(capacity, cell_count(model));
  scratch_ = allocate(backend, particle_scratch_bytes(cell_count(model), line_node_count(model), capacity, sort_bytes));
  point_particle_scratch(a, cell_count(model), line_node_count(model), scratch_.data(), sort_bytes);
  plan_ = allocate(backend, plan_bytes(scene, resolved));

  clear_particles(backend, a);
  hooks_ = make_particle_hooks(scene, resolved, backend, capacity);
  const ParticleCounts none{};
  backend.upload(counts_->data.data(), &none, counts_->bytes());
}

MemoryParts ParticleStage::memory_for(const Scene& scene, const Resolved& resolved) {
  const ParticleParams& p = scene.effects.get<ParticleParams>();
  const std::size_t n = std::size_t(p.capacity);
  const std::size_t fields =
      n * (3 * 2 * sizeof(float) + 2 * sizeof(std::uint32_t)) + sizeof(ParticleCounts);
  // The scratch is per slot and per grid cell: its grid part is what the cells add to it. The cell
  // count is below kMaxGridCells once the scene's checks have passed.
  const Count grid_cells = settings_of(resolved).cells;
  const std::size_t cells = grid_cells.to<std::size_t>(), line_nodes = line_node_count(settings_of(resolved).model);
  const std::size_t per_slot = particle_scratch_bytes(0, 0, p.capacity, sort_scratch_bound(n, 0));
  const std::size_t with_grid = particle_scratch_bytes(cells, line_nodes, p.capacity, sort_scratch_bound(n, cells));
  MemoryParts parts{{"particles.capacity", std::to_string(p.capacity) + " particle slots", Count(fields) + per_slot},
                    {p.cell_mm > 0 ? "particles.cell_mm" : "particles.diameter_mm",
                     "a collision grid of " + std::to_string(grid_cells.value()) + " cells", with_grid - per_slot},
                    {"cut", "a frame's steps and the particles' emitters", Count(plan_bytes(scene, resolved))}};
  for (const MemoryPart& part : particle_hooks_memory(scene, resolved)) parts.push_back(part);
  return parts;
}

// Plans `step`'s emission: the particles each cut has given since the step before, appended to the
// frame's emitters, and the accounting told of them.
void ParticleStage::plan_emission(const State& state, std::uint64_t step, ParticleStep& planned) {
  const double t0 = double(step) / steps_per_s_, t1 = double(step + 1) / steps_per_s_;
  const std::uint64_t capacity = std::uint64_t(args_.arrays.capacity);
  const std::size_t first = emitters_.size();
  std::uint64_t id = accounting_.counts().emitted, total = 0;
  for (const Cut& cut : state.cuts) {
    // The cumulative blood never falls, but its rounding could by an ulp where a beat's flow is
    // least: such a dip emits nothing rather than wrapping the unsigned count.
    const std::uint64_t before = emitted_by(cut, beat_, particle_volume_mm3_, t0);
    const std::uint64_t by_end = emitted_by(cut, beat_, particle_volume_mm3_, t1);
    const std::uint64_t count = by_end > before ? by_end - before : 0;
    if (count == 0) continue;
    // first_new is set once the step's total is known (below).
    emitters_.push_back({float(cut.x_mm), float(cut.y_mm), id, 0u, std::uint32_t(count),
                         float(cut_exit_speed_scale(cut, (t0 + t1) / 2.0, beat_))});
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

void ParticleStage::plan_frame(const State& state, Backend& backend) {
  steps_.assign(std::size_t(substeps_), ParticleStep{});
  emitters_.clear();
  for (int s = 0; s < substeps_; ++s) {
    ParticleStep& planned = steps_[std::size_t(s)];
    const std::uint64_t step = std::uint64_t(state.frames_done) * std::uint64_t(substeps_) + std::uint64_t(s);
    live_range(planned.emit_first_live_slot, planned.emit_live_count);
    plan_emission(state, step, planned);
    live_range(planned.first_live_slot, planned.live_count);
    accounting_.end_step(step);
  }
  // The device's copy of the plan grows with the busiest frame's emitters.
  const std::size_t bytes = steps_.size() * sizeof(ParticleStep) + emitters_.size() * sizeof(Emitter);
  if (bytes > plan_.bytes()) plan_ = allocate(backend, 2 * bytes);
}

void ParticleStage::run(const Scene& scene, State& state, Backend& backend) {
  plan_frame(state, backend);
  ParticleStep* device_steps = plan_.as<ParticleStep>();
  Emitter* device_emitters = reinterpret_cast<Emitter*>(device_steps + steps_.size());
  // The hooks act between one step's integrate and the next step: with any, a run is a step.
  const int run_steps = hooks_.empty() ? substeps_ : 1;
  for (int s = 0; s < substeps_; s += run_steps) {
    launch(backend, ParticleSteps{args_, &steps_[std::size_t(s)], run_steps, emitters_.data(), int(emitters_.size()),
                                  device_steps + s, device_emitters, &graph_});
    if (hooks_.empty()) continue;
    const ParticleStep& step = steps_[std::size_t(s)];
    const ParticleArgs integrated = args_at(args_, step, device_emitters, ParticlePhase::integrate);
    for (const auto& hook : hooks_)
      hook->act(scene, state, backend, integrated, double(step.step) / steps_per_s_,
                double(step.step + 1) / steps_per_s_);
  }
  ParticleCounts counts = accounting_.counts();
  if (scene.effects.has<SuctionParams>()) {
    AspiratedFates fates;
    backend.download(&fates, args_.arrays.fates, sizeof fates);
    counts = with_aspirated(counts, fates);
  }
  backend.upload(counts_->data.data(), &counts, counts_->bytes());
}

namespace {

void resolve_settings(const Scene& scene, Resolved& resolved) { resolved.set(resolve_particles(scene)); }

// The film the particles make, and what of it the mucosa holds against gravity. A film with depth's
// round patch of depth h and radius r stays while ρ·πr²·h·g ≤ τ_y·πr² + ρ·q_p·2πr.
std::string describe_film(const ParticleParams& p, const ParticleSettings& settings) {
  const auto g3 = [](double v) { return format_significant(v, 3); };
  if (p.film_depth) {
    const double g = std::hypot(p.gravity_x_mm_s2, p.gravity_y_mm_s2);
    if (g == 0) return "  film       as deep as it pools; nothing pulls it along the panel\n";
    return "  film       as deep as it pools; the mucosa holds a film up to " + g3(p.yield_mm2_s2 / g) +
           " mm deep against gravity (its yield stress), and a round drop of radius r up to (" + g3(p.yield_mm2_s2) +
           " + 2 × " + g3(p.pinning_mm3_s2) + " / r) / " + g3(g) + " mm deep (its contact line's pinning)\n";
  }
  const DropLimit& drop = settings.drop;
  const std::string film = "  film       " + g3(settings.mechanics.film_mm) + " mm thick; ";
  if (drop.holds_any) return film + "the mucosa holds any drop against gravity\n";
  if (drop.volume_mm3 == 0) return film + "the mucosa holds no drop against gravity (no pinning)\n";
  return film + "the mucosa holds drops up to " + g3(drop.volume_mm3) + " mm³ (radius " + g3(drop.radius_mm) +
         " mm) against gravity\n";
}

// The particle model as the parameters make it (docs/particles.md): the contact, the time step, the
// largest drop the mucosa holds, and whether the ring can hold all the blood the cuts give.
std::string describe_particles(const Scene& scene, const Resolved& resolved, const RunOutline& run) {
  const ParticleParams& p = scene.effects.get<ParticleParams>();
  const ParticleSettings& settings = settings_of(resolved);
  const ParticleMechanics& m = settings.mechanics;
  const auto g3 = [](double v) { return format_significant(v, 3); };
  const std::string limits =
      p.film_depth ? "limits " + g3(m.step_limit_s * 1e3) + " ms for the waves, " +
                         g3(p.diameter_mm / (2.0 * p.max_speed_mm_s) * 1e3) + " ms for half a diameter at max_speed_mm_s"
                   : "limit " + g3(m.step_limit_s * 1e3) + " ms";
  const std::string steps =
      std::to_string(m.substeps) + " sub-steps of " + g3(m.dt_s * 1e3) + " ms (" + limits + ")\n";
  std::string text =
      p.film_depth
          ? "  particles  a film with depth: hydrostatic under " + g3(normal_gravity_mm_s2(p)) + " mm/s², kernel " +
                g3(m.kernel_mm) + " mm, made stable for a " + g3(m.depth_mm) + " mm film, " + steps
          : "  particles  stiffness " + g3(m.stiffness_per_s2) + "/s² (a " + g3(m.depth_mm) + " mm pile at " +
                g3(p.compression) + " compression), " + steps;
  text += describe_film(p, settings);
  const ParticleModel& model = settings.model;
  if (model.rest_steps == 0 || model.rest_steps >= model.lifetime.steps)
    text += "  rest       blood never sleeps (rest_s is 0 or at least lifetime_s)\n";
  else
    text += "  rest       blood that moves less than " + g3(p.rest_speed_mm_s * p.rest_s) + " mm in " + g3(p.rest_s) +
            " s (" + std::to_string(model.rest_steps) + " steps) sleeps until a neighbour moves at " +
            g3(kWakeSpeedFactor * p.rest_speed_mm_s) + " mm/s\n";
  // The ring overwrites live blood when more can be alive at once than it has slots: a cut has at
  // most what it bleeds in its first lifetime alive (its flow only falls).
  double alive = 0;
  for (const Cut& cut : run.cuts)
    alive += std::floor(cut_blood_mm3(cut, cut.start_s + p.lifetime_s, scene.effects.find<PulseParams>()) /
                        p.particle_volume_mm3);
  if (alive > p.capacity)
    text += "warning: the cuts can have up to " + format_fixed(alive, 0) + " particles alive at once (what each " +
            "bleeds within a " + g3(p.lifetime_s) + " s lifetime), more than the ring's " + std::to_string(p.capacity) +
            " slots: it will overwrite live blood; raise [particles].capacity or shorten lifetime_s\n";
  // The film is one particle thick: the panel holds a hexagonal layer of them, and blood past that is
  // squeezed into the layer, past the contact's design (docs/particles.md#incompressible-at-any-depth).
  const double layer = scene.domain.width_mm * scene.domain.height_mm / (std::sqrt(3.0) / 2.0 * p.diameter_mm * p.diameter_mm);
  const double on_panel = std::min(alive, double(p.capacity));
  if (on_panel > layer)
    text += "warning: particles.flow_mm3_per_s_per_mm: the cuts can have " + format_fixed(on_panel, 0) +
            " particles on the panel at once, more than the one layer of film it holds (" + format_fixed(layer, 0) +
            " of " + g3(p.diameter_mm) + " mm, " + g3(m.film_mm) + " mm thick): the film cannot thicken, so the pile " +
            "is squeezed past its design compression; bleed less, or use a larger panel or shorter lifetime_s\n";
  return text;
}

}  // namespace

const Effect<ParticleParams>& particle_effect() {
  static const Effect<ParticleParams> row = [] {
    Effect<ParticleParams> e{particle_table};
    e.stages = {
        {"particles", "particles", declares<ParticleParams>,
         {element_field("particles/position", ElementType::f32, 2, true, "mm",
                        "centre of each ring-buffer slot's particle"),
          element_field("particles/velocity", ElementType::f32, 2, true, "mm/s", "velocity of each slot's particle"),
          element_field("particles/age", ElementType::u32, 1, true, "steps",
                        "steps each slot's particle has lived; a slot holds a live particle while its age is below "
                        "the lifetime (an aspirated particle's age has its top bit, 2^31, set)"),
          element_field("particles/rest", ElementType::u32, 1, true, "steps",
                        "steps each slot's particle has been at rest in a row, up to the model's rest steps, "
                        "where it sleeps (docs/particles.md#rest); with film_depth, 2^32 - 1 while it is being "
                        "born, and 2^31 + the steps since while it joins the film after a birth that ran out "
                        "crowded"),
          element_field("particles/anchor", ElementType::f32, 2, true, "mm",
                        "where each slot's particle began its rest: it is at rest while it stays close to it"),
          element_field("particles/accounting", ElementType::u64, 1, false, "particles",
                        "emitted, alive, expired, overwritten, and with [suction] aspirated: emitted = alive + "
                        "expired + overwritten (+ aspirated)")},
         surface_fields, ParticleStage::memory_for, make_stage<ParticleStage>},
        splat_stage_kind()};
    e.resolve = resolve_settings;
    e.describe = describe_particles;
    return e;
  }();
  return row;
}

}  // namespace bleedsim
