#pragma once
// The hard cases' shared checker (scenarios/hard/*.toml; tests/effects/particle_stability_test.cpp
// and bleeding_hard_test.cpp). run_and_check() runs a scene on the CPU reference and asserts after
// every frame
//   * every slot's position and velocity finite, live or not;
//   * every live particle's centre no further past a wall's line (min_x ≤ x ≤ max_x, min_y ≤ y ≤
//     max_y: where it touches the wall) than wall_reach_mm(): nothing leaves through a wall or
//     falls through the floor, and the walls, contacts with the pair's law (docs/particles.md#walls),
//     give no more than their design allows;
//   * the accounting exact: emitted = alive + expired + overwritten + aspirated (aspirated only
//     in a scene with [suction]), and alive = the number of slots whose age is below the lifetime,
//     counted from the age field;
//   * with [contact] and a scripted [[tip]] path: no live particle's centre inside the tip's body
//     (tip_radius_mm + a particle's radius) while the tip is on the panel, by the kernel's own
//     float test, the tip where the instrument puts it at the frame's last sub-step;
//   * the overlap bounded: the deepest d − |xi − xj| over live pairs past their birth, found with
//     the test's own grid (measure_crowding), below half a diameter (no pair passes through
//     another; a case may lift this for a while that something outside the particles' own
//     physics moves them, saying why), and once the particles have landed below a tenth of a
//     diameter: the contact is made stiff enough for the deepest pile's bottom contacts to overlap
//     ⅔·compression on average, and a settled pile's contact forces are spread exponentially,
//     P(f) ∝ exp(−1.5·f/⟨f⟩) (Mueth, Jaeger & Nagel 1998), so the strongest of n contacts carries
//     about ln(n)/1.5 times the mean: with the default 2 % compression, 1.33 % × ln(10⁵)/1.5 = 10 %
//     for a full-depth pile of 10⁵ contacts (big-pile, with 3·10⁵, takes 1.5 %);
//   * where the case is a burst of births on top of each other, no particle faster than twice the
//     speed a lone particle reaches, g/drag: the burst eases apart rather than blasting apart;
// and over the run that the kinetic energy decays once nothing feeds it: after the last cut stops
// bleeding and, with [contact], the tip has left.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/effects/contact/contact_params.h"
#include "core/effects/particles/particle_accounting.h"
#include "core/effects/particles/particle_model.h"
#include "core/scene/tool.h"
#include "core/simulation/simulation.h"

namespace bleedsim::test {

// scenarios/hard/<name>.toml, and the scene it holds.
std::string hard_scenario(const std::string& name);
Scene load_hard(const std::string& name);

// One frame's particles as the library reports them.
struct Particles {
  std::vector<float> position;  // mm, (x, y) per slot
  std::vector<float> velocity;  // mm/s
  std::vector<std::uint32_t> age;
  ParticleCounts counts;  // aspirated is 0 in a scene without [suction]
  double t_s;             // the frame's time

  explicit Particles(const Simulation& sim);
  int slots() const { return int(age.size()); }
  double speed(int slot) const;  // mm/s, in double
};

// Kinetic energy per unit mass of the live particles, mm²/s².
double kinetic_energy(const ParticleModel& m, const Particles& p);

struct Crowding {
  double max_overlap_mm = 0.0;  // over live pairs whose particles are both at least min_age old
  int max_per_cell = 0;         // most live particles in one of the library's cells (edge cell_mm)
};

// The test's own neighbour search, independent of the library's grid, sort and max_per_cell: a
// uniform grid of one-diameter cells over the panel, a counting sort into it, and every pair in a
// cell and its four forward neighbours examined in double precision. Particles younger than
// min_age steps are left out of the overlap: a new particle is placed at its cut whatever is there
// (coincident with another, or inside a pile), so its overlap measures the emission, not the
// contact model; after min_age steps the contacts have had time to push it out.
Crowding measure_crowding(const ParticleModel& m, const Particles& p, std::uint32_t min_age);

// How far past a wall's line a centre may be pressed (docs/particles.md#walls): the design
// compression ε·d, the most the deepest pile presses into its floor, and v_max/√k_w besides, how far a
// particle at the speed limit sinks into the wall's spring with its kinetic energy (½v² = ½k_w·δ²;
// the wall's dashpot only shortens it).
double wall_reach_mm(const Scene& scene);

// How far the deepest live centre is past a wall's line, mm (0: none touches a wall).
double deepest_into_a_wall_mm(const ParticleModel& m, const Particles& p);

// The first thing wrong with one frame's particles (finite, within wall_reach_mm of the walls, the
// accounting), or "" when all holds.
std::string frame_problem(const ParticleModel& m, const Particles& p, double wall_reach_mm);

// The scripted tip where the instrument puts it after `steps_done` sub-steps (at steps_done /
// steps_per_s, computed as the particle stage computes it), when it is there; and its body's
// radius, the particle centres' keep-out: tip_radius_mm + the particles' radius.
std::optional<ToolSample> tip_after_steps(const Scene& scene, std::uint64_t steps_done);
float tip_body_mm(const Scene& scene);

// The first live particle whose centre is inside the disc (the kernel's own float test), or "".
std::string inside_tip_problem(const ParticleModel& m, const Particles& p, const ToolSample& tip, float body_mm);

// No pair passes through another: its overlap stays below half a diameter, past the new particle's
// birth (until then its forces are weak by design, and coincident births overlap fully).
constexpr double kPassThrough = 0.5;
// At rest: a tenth of a diameter (the header says where the models' compression comes from).
constexpr double kAtRest = 0.10;

// What a case expects beyond the per-frame invariants.
struct Expect {
  // A burst: no particle faster than twice g/drag.
  bool burst = false;
  // The deepest overlap at rest, in diameters.
  double at_rest = kAtRest;
  // The kinetic energy at the last frame below this fraction of the energy when the particles were
  // left alone.
  double end_energy_ratio = 0.01;
  // Most live particles in one of the library's cells at the last frame; 0: unchecked.
  int max_per_cell_at_end = 0;
  // Frames before this time are not held to the pass-through bound (a case says why: a contact
  // tip moving faster than the blood can part puts particles on one another).
  double overlap_unbounded_until_s = 0.0;
};

struct RunSummary {
  std::int64_t frames = 0;
  std::uint64_t steps = 0;
  std::uint64_t max_alive = 0;
  ParticleCounts final_counts;
  double max_overlap_mm = 0.0;  // any frame held to the pass-through bound
  std::int64_t max_overlap_frame = -1;
  double unbounded_overlap_mm = 0.0;  // the frames before Expect::overlap_unbounded_until_s
  double rest_overlap_mm = 0.0;       // the deepest in the last quarter after the particles were left alone
  double max_speed = 0.0;             // mm/s, any frame
  double into_wall_mm = 0.0;          // the deepest any centre went past a wall's line, any frame
  int tip_frames = 0;                 // frames checked for particles inside the tip
  double energy_at_stop = 0.0;        // the first frame at or after the particles were left alone
  double energy_at_end = 0.0;
  double first_quarter_max = 0.0;  // max KE over the first and last quarters of the frames
  double last_quarter_max = 0.0;   // after they were left alone
  int max_per_cell_at_end = 0;
  double seconds = 0.0;
};

// When nothing feeds the particles any more: the last cut has stopped bleeding and, with
// [contact], the scripted tip has left.
double left_alone_s(const Scene& scene);

// Runs a scene to its end on the CPU reference, checking every frame; then the energy's decay and
// the end state's crowding. Stops at the first frame that breaks an invariant. `each_frame`, when
// given, sees every frame's particles too (its own assertions stop the run when fatal).
void run_and_check(const std::string& name, Scene scene, const Expect& expect, RunSummary* out,
                   const std::function<void(const Particles&)>& each_frame = nullptr);

}  // namespace bleedsim::test
