#include "core/effects/cuts.h"

#include <cmath>

#include "core/effects/particles/particle_params.h"
#include "core/effects/pulse/pulse_params.h"
#include "core/effects/spread/spread_params.h"
#include "core/effects/vessels/vessel_params.h"
#include "core/runtime/message_text.h"

namespace bleedsim {
namespace {

// A cut's size and flow default to the scene's [spread] and [particles]; a flow given without
// particles would do nothing, and a file saying so is mistaken.
ParamProblem defaults_from_scene(Cut& cut, const Written& written, const Scene& scene) {
  const Cut wound = cut_at(scene, cut.x_mm, cut.y_mm, cut.start_s);
  for (const auto& [key, member] :
       {std::pair{"radius_mm", &Cut::radius_mm}, std::pair{"growth_per_s", &Cut::growth_per_s},
        std::pair{"flow_mm3_per_s_per_mm", &Cut::flow_mm3_per_s_per_mm}, std::pair{"bleed_s", &Cut::bleed_s},
        std::pair{"clot_s", &Cut::clot_s}})
    if (!written.has(key)) cut.*member = wound.*member;
  for (const char* key : {"wound_mm", "flow_mm3_per_s_per_mm", "bleed_s", "clot_s"})
    if (written.has(key) && !scene.effects.has<ParticleParams>())
      return {key, "has no effect: this scene declares no [particles]"};
  if (written.has("arterial") && !scene.effects.has<PulseParams>())
    return {"arterial", "has no effect: this scene declares no [pulse]"};
  if (written.has("wound_angle_deg") && !scene.effects.has<VesselParams>())
    return {"wound_angle_deg", "has no effect: this scene declares no [vessels]"};
  return {};
}

// Any finite position: the panel's rule (below) says where a cut may be.
const Range kAnywhere{-HUGE_VAL, HUGE_VAL};

ParamProblem within(const char* key, double v, double size_mm) {
  if (v >= 0 && v <= size_mm) return {};
  return {key, "must be between 0 and " + format_number(size_mm) + " (got " + format_number(v) + ")"};
}

ParamProblem on_the_panel(const Cut& cut, const Scene& scene) {
  if (ParamProblem problem = within("x_mm", cut.x_mm, scene.domain.width_mm)) return problem;
  return within("y_mm", cut.y_mm, scene.domain.height_mm);
}

// At most kMaxParticleRate particles a second from one cut: a step's count stays well inside 32 bits.
ParamProblem countable(const Cut& cut, const Scene& scene) {
  const ParticleParams* particles = scene.effects.find<ParticleParams>();
  if (!particles) return {};
  const double rate = cut.wound_mm * cut.flow_mm3_per_s_per_mm / particles->particle_volume_mm3;
  if (rate <= kMaxParticleRate) return {};
  return {"flow_mm3_per_s_per_mm", "gives " + format_number(rate) +
                                       " particles per second (wound_mm × "
                                       "flow_mm3_per_s_per_mm / particle_volume_mm3); at most " +
                                       format_number(kMaxParticleRate)};
}

}  // namespace

Cut cut_at(const Scene& scene, double x_mm, double y_mm, double start_s) {
  const SpreadParams* spread = scene.effects.find<SpreadParams>();
  const ParticleParams* particles = scene.effects.find<ParticleParams>();
  const SpreadParams size = spread ? *spread : SpreadParams{};
  const ParticleParams flow = particles ? *particles : ParticleParams{};
  return Cut{x_mm,         y_mm,       start_s, size.radius_mm, size.growth_per_s, 1.0, flow.flow_mm3_per_s_per_mm,
             flow.bleed_s, flow.clot_s};
}

const ParamTable<Cut>& cut_table() {
  using T = ParamType;
  using P = Cut;
  const auto& size = spread_table();
  const auto& flow = particle_table();
  static const ParamTable<P> table{
      "cut",
      "one table per cut: where, when, and (optionally) how large a wound and how hard it bleeds particles",
      {{"x_mm", T::number, BLEEDSIM_MEMBER(P, x_mm), "mm", kAnywhere, "from the panel's left edge", nullptr, true,
        "between 0 and width_mm"},
       {"y_mm", T::number, BLEEDSIM_MEMBER(P, y_mm), "mm", kAnywhere, "from the panel's top edge (y down)", nullptr,
        true, "between 0 and height_mm"},
       {"start_s", T::number, BLEEDSIM_MEMBER(P, start_s), "s", {0, 86400}, "when the cut is made"},
       {"radius_mm", T::number, BLEEDSIM_MEMBER(P, radius_mm), "mm", param_named(size, "radius_mm").range,
        "the stain's radius", "[spread].radius_mm"},
       {"growth_per_s", T::number, BLEEDSIM_MEMBER(P, growth_per_s), "1/s", param_named(size, "growth_per_s").range,
        "the stain's growth", "[spread].growth_per_s"},
       {"wound_mm", T::number, BLEEDSIM_MEMBER(P, wound_mm), "mm", {0, 1e4},
        "the length of wound it stands for: it bleeds in proportion; only with [particles]"},
       {"flow_mm3_per_s_per_mm", T::number, BLEEDSIM_MEMBER(P, flow_mm3_per_s_per_mm), "mm³/s/mm",
        param_named(flow, "flow_mm3_per_s_per_mm").range, "blood per second per mm of wound, as it starts",
        "[particles].flow_mm3_per_s_per_mm"},
       {"bleed_s", T::number, BLEEDSIM_MEMBER(P, bleed_s), "s", param_named(flow, "bleed_s").range,
        "how long it bleeds", "[particles].bleed_s"},
       {"clot_s", T::number, BLEEDSIM_MEMBER(P, clot_s), "s", param_named(flow, "clot_s").range,
        "the flow falls as exp(−t / clot_s) after the cut; 0: it does not", "[particles].clot_s"},
       {"arterial", T::flag, BLEEDSIM_MEMBER(P, arterial), "", {},
        "it spurts with the heartbeat; only with [pulse]",
        "false, or with [vessels] whether its wound reaches [pulse].arterial_density"},
       {"wound_angle_deg", T::number, BLEEDSIM_MEMBER(P, wound_angle_deg), "°", {-360, 360},
        "the wound's direction (0: along x, 90: along y), centred on the cut; only with [vessels]"}},
      {{"the cut lies on the panel: 0 ≤ x_mm ≤ width_mm, 0 ≤ y_mm ≤ height_mm", on_the_panel},
       {"with [particles], wound_mm × flow_mm3_per_s_per_mm / particle_volume_mm3 is at most 1e8 particles a second",
        countable}},
      defaults_from_scene};
  return table;
}

}  // namespace bleedsim
