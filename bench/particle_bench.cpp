// The particle step's phases against the 1 ms haptic tick, in the state a running scene spends its
// time in: a settled pile. Emit, bin (cell keys, stable sort, cell ranges, sorted copies), collide,
// integrate and the whole step as a scene runs it (emit + bin + collide + integrate; on CUDA fused
// into four launches and CUB's scan); the instrument's part of a step
// (core/effects/suction/suction_hook.h, core/effects/contact/contact_hook.h) with its tip in the pile: the suction at
// the default flow's quota and at the whole reach, the contact of a tip moving through it, and the step with both; on
// CUDA at 65,536, 1,048,576 and 4,194,304 particles and on the CPU reference at 65,536; and the grid step against an
// all-pairs baseline (bench/all_pairs.h) at 65,536 on CUDA and 8,192 on the CPU.
//
// The scene is built here, not read from a file: the default ParticleParams, [suction] and
// [contact] at 30 Hz, a panel as wide as the pile and twice its height, the N particles (capacity
// N) on a hexagonal lattice at its bottom, √(N/16) rows deep (at least 24: 64 rows at 65,536, 512
// at 4,194,304, so that the panel stays under two metres wide and float32 positions resolve its
// overlaps), at rest and past their birth (their pairs at full strength). The contact is the
// model's, made stiff for that pile. It runs kSettleSteps steps (more, in chunks, while more than
// kStillMoving of its particles drift faster than kMovingSpeed over a chunk) and only then is it
// timed; the settled state is kept on the backend and restored before every timed run that changes
// it, so each run starts from the same pile. One pile is settled per size and backend and shared by
// that size's phases; the counters say how much of it still moves. The model makes one neighbour
// pass a step (collide): the collide phase's time is its cost per neighbour pass (the per_pass_ms
// counter), the figure to compare with a model that iterates; the step's neighbour_passes counter
// says how many a step makes. The instrument's tip is at the middle of the pile's width, one
// suction radius under its surface (the whole reach in blood), moving sideways at kTipSpeed; its
// cases run the hooks' act_at, the launches a scene's sub-step makes, with the tip and quota given
// here.
// docs/benchmarks.md ("Particles") says what each number means.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "bench/all_pairs.h"
#include "bench/bench_util.h"
#include "core/effects/contact/contact_hook.h"
#include "core/effects/contact/contact_params.h"
#include "core/effects/effect_list.h"
#include "core/effects/particles/particle_buffers.h"
#include "core/effects/particles/particle_model.h"
#include "core/effects/particles/particle_params.h"
#include "core/effects/suction/suction_hook.h"
#include "core/effects/suction/suction_params.h"
#include "core/physics/particles.h"
#include "core/runtime/backend.h"
#include "core/scene/scene.h"

namespace bleedsim {
namespace {

constexpr double kHapticTickMs = 1.0;
constexpr int kMinRows = 24;            // the pile's depth in particles, at least
constexpr int kSettleSteps = 600;       // 0.03-0.1 s of physics at the pile's fewest sub-steps
constexpr int kSettleChunk = 500;       // then more, while it still moves ...
constexpr int kSettleMaxSteps = 20000;  // ... up to this many in all (a deep pile rings for a while)
constexpr double kMovingSpeed = 1.0;    // mm/s: "moving" in the moving_% counter (a tenth of what a
                                        // lone particle slides at): a particle's net displacement over
                                        // the last chunk by the chunk's time. Not its velocity: in a
                                        // deep pile float32 positions ring at ulp·√(6k), a few mm/s at
                                        // 4M particles, in place (max_speed_mm_s shows it).
constexpr double kStillMoving = 0.01;   // settled: at most 1 % of the particles moving
constexpr int kEmitters = 64;           // the emit burst: 4 new particles from each of 64 cuts above
constexpr int kPerEmitter = 4;          // the pile (a heavy bleed, not a crowd: none is born in a
                                        // crowd, whose cost grows as its square)
constexpr int kIterations = 20;         // timed runs per repetition
constexpr int kAllPairsIterations = 5;  // the O(N²) baseline is slow
constexpr int kRepetitions = 5;
constexpr int kNeighbourPassesPerStep = 1;  // collide_particle: the model does not iterate
constexpr double kTipSpeed = 20.0;          // mm/s: the instrument's tip, sideways through the pile

enum class Work {
  emit, bin, collide, integrate, step, all_pairs_step,
  suction, suction_whole_reach, contact, step_with_instrument
};

const char* name_of(Work work) {
  switch (work) {
    case Work::emit: return "emit";
    case Work::bin: return "bin";
    case Work::collide: return "collide";
    case Work::integrate: return "integrate";
    case Work::step: return "step";
    case Work::all_pairs_step: return "all_pairs_step";
    case Work::suction: return "suction";
    case Work::suction_whole_reach: return "suction_whole_reach";
    case Work::contact: return "contact";
    case Work::step_with_instrument: return "step_with_instrument";
  }
  return "?";
}

// The pile's rows and the slots per lattice row.
int rows_for(int n) { return std::max(kMinRows, int(std::lround(std::sqrt(n / 16.0)))); }
int columns_for(int n) { return (n + rows_for(n) - 1) / rows_for(n); }

// The scene: default particle parameters, a panel that holds the pile with as much room above it.
Scene pile_scene(int n) {
  Scene scene;
  scene.name = "settled pile (bench/particle_bench.cpp)";
  scene.seed = 1;
  scene.effects.set(ParticleParams{});
  scene.effects.set(SuctionParams{});
  scene.effects.set(ContactParams{});
  ParticleParams& p = scene.effects.get<ParticleParams>();
  p.capacity = n;
  const double pile_height_mm = (rows_for(n) - 1) * std::sqrt(3.0) / 2.0 * p.diameter_mm + p.diameter_mm;
  // Even rows start at one radius from the left edge, odd rows at one diameter: the odd rows'
  // last particle touches the right edge.
  scene.domain.width_mm = columns_for(n) * p.diameter_mm + p.diameter_mm / 2.0;
  scene.domain.height_mm = 2.0 * pile_height_mm;
  // No pixels: draw is not timed here.
  // No particle expires while it is measured: a day (the most a scene may ask), or 1e9 steps.
  const double steps_per_s = resolve_particles(p, scene).steps_per_s;
  p.lifetime_s = std::min(86400.0, 1.0e9 / steps_per_s);
  // Awake throughout: a step's cost whatever has come to rest.
  p.rest_s = 0.0;
  return scene;
}

// A pile of N particles on one backend: its scene, its arrays, the emit burst, and its settled
// state (kept on the backend so restoring it costs a device copy, not a host upload).
struct Pile {
  std::unique_ptr<Backend> backend;
  int n;
  int threads;  // the CPU all-pairs baseline's, as many as the CPU backend's
  Scene scene;
  ParticleArgs args{};
  Buffer position, velocity, age, rest, anchor, scratch, emitters, plan;
  std::vector<Emitter> cuts;              // the emit burst's, on the host as a scene plans them
  std::unique_ptr<TwinCache> step_cache;  // what a backend keeps between whole steps
  Buffer settled_position, settled_velocity, settled_age, settled_rest, settled_anchor;
  std::string problem;  // why it cannot be measured (empty when it can)
  int settle_steps = 0;
  double ke_per_particle = 0.0;  // ½|v|² per unit mass, mm²/s², mean over the particles
  double max_speed = 0.0;        // mm/s
  double moving_share = 0.0;     // of the particles, drifting faster than kMovingSpeed
  std::vector<float> last_xy;    // positions at the last measure(), for the drift
  double bottom_overlap = 0.0;   // mm: the bottom row's overlap with the row above, mean
  std::optional<SuctionHook> suction;    // the instrument's tip in the settled pile, sucking ...
  std::optional<ContactHook> contact;    // ... and touching:
  ToolSample tip, tip_before;            // where it is, and where it was a sub-step before
  double flow_per_step = 0.0;            // the default flow's particles a sub-step, on average
  std::uint32_t flow_quota = 0;          // ... and its quota in its busiest steps
  std::uint32_t reach = 0;               // particles within the suction's reach
  int in_body = 0;                       // particles inside the tip's body, which contact moves

  Pile(std::unique_ptr<Backend> b, int count)
      : backend(std::move(b)), n(count), threads(int(std::max(1u, std::thread::hardware_concurrency()))),
        scene(pile_scene(count)) {
    problem = check_params(particle_table(), scene.effects.get<ParticleParams>(), scene).message;
    if (!problem.empty()) return;
    const ParticleModel model = resolve_particles(scene).model;
    args.model = model;
    ParticleArrays& a = args.arrays;
    a.capacity = n;
    args.live_count = n;  // the ring is full: every slot, from any first slot, is live
    args.first_live_slot = 0;
    const std::size_t pairs = 2 * std::size_t(n) * sizeof(float), words = std::size_t(n) * sizeof(std::uint32_t);
    position = backend->allocate(pairs);
    velocity = backend->allocate(pairs);
    age = backend->allocate(words);
    rest = backend->allocate(words);
    anchor = backend->allocate(pairs);
    a.position = position.as<float>();
    a.velocity = velocity.as<float>();
    a.age = age.as<std::uint32_t>();
    a.rest = rest.as<std::uint32_t>();
    a.anchor = anchor.as<float>();
    const std::size_t sort_bytes = backend->particle_sort_scratch_bytes(n, cell_count(model));
    scratch = backend->allocate(particle_scratch_bytes(cell_count(model), line_node_count(model), n, sort_bytes));
    point_particle_scratch(a, cell_count(model), line_node_count(model), scratch.data(), sort_bytes);
    clear_particles(*backend, a);  // every slot at rest; scratch defined

    // The lattice: slot s in row s / columns (row 0 at the bottom), spacing one diameter, born.
    const int columns = columns_for(n);
    const double d = scene.effects.get<ParticleParams>().diameter_mm, r = d / 2.0, row_mm = std::sqrt(3.0) / 2.0 * d;
    const double bottom = scene.domain.height_mm - r;
    std::vector<float> xy(2 * std::size_t(n));
    for (int s = 0; s < n; ++s) {
      const int row = s / columns, column = s % columns;
      xy[2 * s] = float(r + column * d + (row % 2 ? r : 0.0));
      xy[2 * s + 1] = float(bottom - row * row_mm);
    }
    backend->upload(a.position, xy.data(), pairs);
    const std::vector<std::uint32_t> ages(n, std::uint32_t(model.birth_steps));
    backend->upload(a.age, ages.data(), words);

    // The burst: kPerEmitter new particles from each of kEmitters cuts spread over the free space
    // above the pile (ids N, N + 1, …, so they overwrite the oldest slots, the bottom of the pile).
    const int burst = kEmitters * kPerEmitter;
    for (int e = 0; e < kEmitters; ++e) {
      const int first = burst * e / kEmitters, next = burst * (e + 1) / kEmitters;
      cuts.push_back({float(scene.domain.width_mm * (2 * e + 1) / (2 * kEmitters)),
                      float(scene.domain.height_mm / 4.0), std::uint64_t(n) + std::uint64_t(first),
                      std::uint32_t(first), std::uint32_t(next - first)});
    }
    emitters = backend->allocate(cuts.size() * sizeof(Emitter));
    backend->upload(emitters.data(), cuts.data(), emitters.bytes());
    args.emitters = emitters.as<const Emitter>();
    args.emitter_count = kEmitters;
    args.new_count = burst;
    plan = backend->allocate(sizeof(ParticleStep));

    settle();
    settled_position = backend->allocate(pairs);
    settled_velocity = backend->allocate(pairs);
    settled_age = backend->allocate(words);
    settled_rest = backend->allocate(words);
    settled_anchor = backend->allocate(pairs);
    copy(settled_position.data(), a.position, pairs);
    copy(settled_velocity.data(), a.velocity, pairs);
    copy(settled_age.data(), a.age, words);
    copy(settled_rest.data(), a.rest, words);
    copy(settled_anchor.data(), a.anchor, pairs);
    backend->synchronize();

    // The instrument: its tip one suction radius under the pile's surface (its highest centre), at
    // the middle of its width. What it does there is measured on the backend, once each, undone.
    const Resolved resolved = resolve(scene);
    suction.emplace(scene, resolved, *backend, n);
    contact.emplace(scene, resolved, *backend, n);
    double top = scene.domain.height_mm;  // y grows downward
    for (std::size_t i = 1; i < last_xy.size(); i += 2) top = std::min(top, double(last_xy[i]));
    tip = {0.0, scene.domain.width_mm / 2.0, top + scene.effects.get<SuctionParams>().radius_mm, true, kEveryButton};
    tip_before = tip;
    tip_before.x_mm -= kTipSpeed * args.model.dt_s;
    flow_per_step = resolved.get<SuctionSettings>().particles_per_step;
    flow_quota = std::uint32_t(std::ceil(flow_per_step));
    reach = std::uint32_t(taken_by(std::uint32_t(n)));
    in_body = moved_by_contact();
  }

  void emit() { backend->run("particles", ParticlePhase::emit, args); }
  void bin() { backend->run("particles", ParticlePhase::bin, args); }
  void collide() { backend->run("particles", ParticlePhase::collide, args); }
  void integrate() { backend->run("particles", ParticlePhase::integrate, args); }
  // The whole step, as a scene's sub-step runs it (core/effects/particles/particle_stage.cpp): on CUDA its
  // phases fused into four launches and CUB's scan, the same bytes as the four phases one by one.
  void step() {
    ParticleStep planned{};  // the ring is full: the live range is the same before emission and after
    planned.step = args.step;
    planned.emitter_count = args.emitter_count;
    planned.new_count = args.new_count;
    planned.emit_first_live_slot = planned.first_live_slot = args.first_live_slot;
    planned.emit_live_count = planned.live_count = args.live_count;
    backend->run("particles", ParticleSteps{args, &planned, 1, cuts.data(), int(cuts.size()),
                                            plan.as<ParticleStep>(), emitters.as<Emitter>(), &step_cache});
  }
  void all_pairs_collide() {
    if (backend->kind() == BackendKind::cpu) {
      all_pairs_collide_cpu(args.arrays, args.model, threads);
      return;
    }
#if BLEEDSIM_HAVE_CUDA
    all_pairs_collide_cuda(args.arrays, args.model);
#endif
  }
  void all_pairs_step() { emit(); all_pairs_collide(); integrate(); }
  // The instrument's launches in a sub-step: the suction taking up to `quota` (none at 0), the
  // contact when `touching`.
  void instrument_acts(std::uint32_t quota, bool touching) {
    suction->act_at(*backend, args, tip, quota);
    if (touching) contact->act_at(*backend, args, tip, tip_before, args.model.dt_s);
  }
  void step_with_instrument() { step(); instrument_acts(flow_quota, true); }

  // Particles the suction takes from the settled pile with this quota (one run, undone).
  std::uint64_t taken_by(std::uint32_t quota) {
    const std::uint64_t before = aspirated();
    restore();
    instrument_acts(quota, false);
    const std::uint64_t taken = aspirated() - before;
    restore();
    return taken;
  }

  // Back to the settled pile: the state a phase changes (positions, velocities, ages, rest, anchors).
  void restore() {
    const std::size_t pairs = 2 * std::size_t(n) * sizeof(float), words = std::size_t(n) * sizeof(std::uint32_t);
    copy(args.arrays.position, settled_position.data(), pairs);
    copy(args.arrays.velocity, settled_velocity.data(), pairs);
    copy(args.arrays.age, settled_age.data(), words);
    copy(args.arrays.rest, settled_rest.data(), words);
    copy(args.arrays.anchor, settled_anchor.data(), pairs);
  }

 private:
  std::uint64_t aspirated() {
    AspiratedFates fates;
    backend->download(&fates, args.arrays.fates, sizeof fates);
    return fates.aspirated;
  }

  // Particles the tip's body moves in the settled pile (one run, undone).
  int moved_by_contact() {
    const std::size_t count = 2 * std::size_t(n);
    std::vector<float> before(count), after(count);
    restore();
    backend->download(before.data(), args.arrays.position, count * sizeof(float));
    instrument_acts(0, true);
    backend->download(after.data(), args.arrays.position, count * sizeof(float));
    restore();
    int moved = 0;
    for (int s = 0; s < n; ++s) moved += before[2 * s] != after[2 * s] || before[2 * s + 1] != after[2 * s + 1];
    return moved;
  }

  void copy(void* dst, const void* src, std::size_t bytes) {
    if (backend->kind() == BackendKind::cpu) {
      std::memcpy(dst, src, bytes);
      return;
    }
#if BLEEDSIM_HAVE_CUDA
    copy_device_to_device_cuda(dst, src, bytes);
#endif
  }

  void settle() {
    const auto run = [&](int steps) {
      for (int s = 0; s < steps; ++s) {
        bin();
        collide();
        integrate();
      }
      settle_steps += steps;
      measure(steps);
    };
    run(kSettleSteps);
    while (moving_share > kStillMoving && settle_steps < kSettleMaxSteps) run(kSettleChunk);
    if (moving_share > kStillMoving)
      problem = "the pile did not settle in " + std::to_string(settle_steps) + " steps: " +
                std::to_string(100 * moving_share) + " % of its particles drift faster than " +
                std::to_string(kMovingSpeed) + " mm/s (at most " + std::to_string(100 * kStillMoving) +
                " %), fastest " + std::to_string(max_speed) + " mm/s";
    args.step = std::uint64_t(settle_steps);  // the burst's jitter: as if emitted in the next step
  }

  // The state after `steps` more steps: energy, fastest particle, drift since the last call.
  void measure(int steps) {
    const std::size_t count = 2 * std::size_t(n);
    std::vector<float> v(count), xy(count);
    backend->download(v.data(), args.arrays.velocity, count * sizeof(float));
    backend->download(xy.data(), args.arrays.position, count * sizeof(float));
    const double chunk_s = steps * double(args.model.dt_s);
    double energy = 0.0, fastest = 0.0;
    int moving = 0;
    for (int s = 0; s < n; ++s) {
      const double speed_sq = double(v[2 * s]) * v[2 * s] + double(v[2 * s + 1]) * v[2 * s + 1];
      energy += 0.5 * speed_sq;
      fastest = std::max(fastest, speed_sq);
      if (last_xy.empty()) continue;
      const double drift = std::hypot(double(xy[2 * s]) - last_xy[2 * s], double(xy[2 * s + 1]) - last_xy[2 * s + 1]);
      moving += drift > kMovingSpeed * chunk_s;
    }
    ke_per_particle = energy / n;
    max_speed = std::sqrt(fastest);
    moving_share = last_xy.empty() ? 1.0 : double(moving) / n;
    last_xy = xy;
    // Each bottom-row particle's deepest overlap with the row above (its lattice neighbours).
    const int columns = columns_for(n);
    const double d = scene.effects.get<ParticleParams>().diameter_mm;
    double overlap = 0.0;
    int counted = 0;
    for (int j = 0; j < columns && j < n; ++j) {
      double nearest = INFINITY;
      for (int k = std::max(0, j - 2); k <= std::min(columns - 1, j + 2); ++k) {
        const int other = columns + k;
        if (other >= n) continue;
        const double dx = double(xy[2 * j]) - xy[2 * other], dy = double(xy[2 * j + 1]) - xy[2 * other + 1];
        nearest = std::min(nearest, std::sqrt(dx * dx + dy * dy));
      }
      if (nearest == INFINITY) continue;
      overlap += std::max(0.0, d - nearest);
      ++counted;
    }
    bottom_overlap = counted ? overlap / counted : 0.0;
  }
};

// One pile at a time: the benchmarks of a size and backend run one after another and share it;
// the next size frees it before settling its own.
std::unique_ptr<Pile>& cached_pile() {
  static std::unique_ptr<Pile> pile;
  return pile;
}

Pile* pile_or_skip(BackendKind kind, int n, benchmark::State& state) {
  std::unique_ptr<Pile>& pile = cached_pile();
  if (pile && pile->backend->kind() == kind && pile->n == n) return pile.get();
  pile.reset();
  std::unique_ptr<Backend> backend = backend_or_skip(kind, state);
  if (!backend) return nullptr;
  pile = std::make_unique<Pile>(std::move(backend), n);
  return pile.get();
}

// Milliseconds of `work` over the repetition's runs, each after `prepare` (not timed).
double time_runs(benchmark::State& state, Pile& pile, const std::function<void()>& prepare,
                 const std::function<void()>& work) {
  for (int i = 0; i < kWarmUpRuns; ++i) {
    prepare();
    work();
  }
  double total_ms = 0.0;
  for (auto _ : state) {
    prepare();
    const double ms = pile.backend->time_ms(work);
    state.SetIterationTime(ms / 1000.0);
    total_ms += ms;
  }
  return total_ms / double(state.iterations());
}

// The grid step's median over kIterations runs, beside the all-pairs step and the step with the
// instrument.
double grid_step_ms(Pile& pile) {
  std::vector<double> ms;
  for (int i = 0; i < kWarmUpRuns + kIterations; ++i) {
    pile.restore();
    const double t = pile.backend->time_ms([&] { pile.step(); });
    if (i >= kWarmUpRuns) ms.push_back(t);
  }
  std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
  return ms[ms.size() / 2];
}

void time_particles(benchmark::State& state, BackendKind kind, int n, Work work) {
  try {
    Pile* pile = pile_or_skip(kind, n, state);
    if (!pile) return;
    if (!pile->problem.empty()) {
      state.SkipWithError(("particles not measured: " + pile->problem).c_str());
      return;
    }
    // A consistent start: the settled pile, binned, its contacts known (collide and integrate
    // read what bin and collide leave).
    pile->restore();
    pile->bin();
    pile->collide();
    const std::function<void()> restore = [pile] { pile->restore(); }, nothing = [] {};
    const std::uint32_t quota = work == Work::suction_whole_reach ? pile->reach : pile->flow_quota;
    double ms = 0.0, grid_ms = 0.0;
    switch (work) {
      case Work::emit: ms = time_runs(state, *pile, restore, [pile] { pile->emit(); }); break;
      case Work::bin: ms = time_runs(state, *pile, nothing, [pile] { pile->bin(); }); break;
      case Work::collide: ms = time_runs(state, *pile, nothing, [pile] { pile->collide(); }); break;
      case Work::integrate: ms = time_runs(state, *pile, restore, [pile] { pile->integrate(); }); break;
      case Work::step: ms = time_runs(state, *pile, restore, [pile] { pile->step(); }); break;
      case Work::all_pairs_step:
        grid_ms = grid_step_ms(*pile);
        ms = time_runs(state, *pile, restore, [pile] { pile->all_pairs_step(); });
        break;
      // The instrument's cases change the pile (particles taken, moved): each run starts from it.
      case Work::suction:
      case Work::suction_whole_reach:
        ms = time_runs(state, *pile, restore, [pile, quota] { pile->instrument_acts(quota, false); });
        break;
      case Work::contact: ms = time_runs(state, *pile, restore, [pile] { pile->instrument_acts(0, true); }); break;
      case Work::step_with_instrument:
        grid_ms = grid_step_ms(*pile);
        ms = time_runs(state, *pile, restore, [pile] { pile->step_with_instrument(); });
        break;
    }
    pile->restore();
    pile->backend->synchronize();
    state.counters["ms"] = ms;
    state.counters["haptic_tick_%"] = 100.0 * ms / kHapticTickMs;
    state.counters["particle_steps/s"] = double(n) * 1e3 / ms;
    if (work == Work::emit) state.counters["new_particles"] = pile->args.new_count;
    if (work == Work::collide) state.counters["per_pass_ms"] = ms;
    if (work == Work::step) state.counters["neighbour_passes"] = kNeighbourPassesPerStep;
    if (work == Work::all_pairs_step) {
      state.counters["grid_step_ms"] = grid_ms;
      state.counters["all_pairs/grid"] = ms / grid_ms;
    }
    const bool sucks = work == Work::suction || work == Work::suction_whole_reach || work == Work::step_with_instrument;
    if (sucks) {
      state.counters["candidates"] = pile->reach;
      state.counters["quota"] = quota;
      state.counters["taken"] = double(pile->taken_by(quota));
      state.counters["flow_particles/step"] = pile->flow_per_step;
    }
    if (work == Work::contact || work == Work::step_with_instrument) state.counters["in_body"] = pile->in_body;
    if (work == Work::step_with_instrument) state.counters["step_ms"] = grid_ms;
    state.counters["ke_per_particle"] = pile->ke_per_particle;
    state.counters["max_speed_mm_s"] = pile->max_speed;
    state.counters["moving_%"] = 100.0 * pile->moving_share;
    state.counters["bottom_overlap_mm"] = pile->bottom_overlap;
    state.counters["settle_steps"] = pile->settle_steps;
    state.SetLabel(pile->backend->device_name());
  } catch (const std::exception& e) {
    state.SkipWithError((std::string("particles not measured: ") + e.what()).c_str());
  }
}

void register_case(BackendKind kind, int n, Work work) {
  const std::string name = std::string("Particle/") + to_string(kind) + "/" + name_of(work) + "/" + std::to_string(n);
  benchmark::RegisterBenchmark(name.c_str(), [kind, n, work](benchmark::State& state) {
    time_particles(state, kind, n, work);
  })
      ->UseManualTime()
      ->Iterations(work == Work::all_pairs_step ? kAllPairsIterations : kIterations)
      ->Unit(benchmark::kMillisecond)
      ->Repetitions(kRepetitions)
      ->ReportAggregatesOnly(true)
      ->DisplayAggregatesOnly(true);
}

}  // namespace

void register_particle_benchmarks() {
  // Grouped by backend and size, so each pile is settled once.
  const Work phases[] = {Work::emit,    Work::bin,     Work::collide,             Work::integrate,
                         Work::step,    Work::suction, Work::suction_whole_reach, Work::contact,
                         Work::step_with_instrument};
  for (const Work work : phases) register_case(BackendKind::cpu, 65536, work);
  // The CPU baseline at a size where O(N²) runs in seconds, beside the grid step at that size.
  register_case(BackendKind::cpu, 8192, Work::step);
  register_case(BackendKind::cpu, 8192, Work::all_pairs_step);
  for (const int n : {65536, 1048576, 4194304}) {
    for (const Work work : phases) register_case(BackendKind::cuda, n, work);
    if (n == 65536) register_case(BackendKind::cuda, n, Work::all_pairs_step);
  }
}

void release_particle_benchmarks() { cached_pile().reset(); }

}  // namespace bleedsim
