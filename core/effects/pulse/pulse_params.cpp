#include "core/effects/pulse/pulse_params.h"

#include <cmath>

#include "core/effects/effect.h"
#include "core/effects/particles/particle_params.h"
#include "core/effects/vessels/vessel_params.h"
#include "core/runtime/message_text.h"

namespace bleedsim {
namespace {

// The waveform never reverses the flow (w ≥ 1 − a₁ − a₂ > 0), and its spectrum peaks at the heart
// rate (a₂ < a₁).
ParamProblem flow_stays_forward(const PulseParams& p, const Scene&) {
  if (p.systolic + p.dicrotic >= 1.0)
    return {"dicrotic", "systolic + dicrotic must be below 1, or the flow would stop or reverse in each beat (got " +
                            format_number(p.systolic + p.dicrotic) + ")"};
  if (p.dicrotic >= p.systolic)
    return {"dicrotic", "must be below systolic (" + format_number(p.systolic) +
                            "): the beat is the waveform's strongest part"};
  return {};
}

// A spurt at the waveform's peak is still within the particles' speed limit.
ParamProblem spurt_within_speed_limit(const PulseParams& p, const Scene& scene) {
  const ParticleParams* particles = scene.effects.find<ParticleParams>();
  if (!particles) return {"heart_rate_per_min", "has no effect: this scene declares no [particles]"};
  const ParticleParams& q = *particles;
  const double fastest = (1.0 + p.systolic + p.dicrotic) * std::hypot(q.velocity_x_mm_s, q.velocity_y_mm_s) +
                         std::sqrt(2.0) * q.velocity_jitter_mm_s;
  if (fastest <= q.max_speed_mm_s) return {};
  return {"systolic", "makes an arterial spurt of up to " + format_number(fastest) +
                          " mm/s ((1 + systolic + dicrotic) × |particles.velocity_mm_s| + √2 × velocity_jitter_mm_s), "
                          "past particles.max_speed_mm_s = " +
                          format_number(q.max_speed_mm_s)};
}

std::string describe_pulse(const Scene& scene, const Resolved&, const RunOutline&) {
  const PulseParams& q = scene.effects.get<PulseParams>();
  return "  pulse      " + format_significant(q.heart_rate_per_min, 6) + " beats a minute, w(t) = 1 + " +
         format_significant(q.systolic, 6) + " sin(2πft) + " + format_significant(q.dicrotic, 6) +
         " sin(4πft); arterial: cuts marked so" +
         (scene.effects.has<VesselParams>()
              ? ", and wounds of mean vessel density ≥ " + format_number(q.arterial_density)
              : std::string()) +
         "\n";
}

}  // namespace

const ParamTable<PulseParams>& pulse_table() {
  using P = PulseParams;
  using T = ParamType;
  static const ParamTable<P> table{
      "pulse",
      "declares a heartbeat: arterial wounds spurt with it, venous ones ooze steadily (needs [particles])",
      {{"heart_rate_per_min", T::number, BLEEDSIM_MEMBER(P, heart_rate_per_min), "1/min", {0, 300, true},
        "beats a minute; the heart beats from t = 0"},
       {"systolic", T::number, BLEEDSIM_MEMBER(P, systolic), "", {0, 1},
        "a₁ in w(t) = 1 + a₁ sin(2πft) + a₂ sin(4πft): the beat's swing of the flow about its mean"},
       {"dicrotic", T::number, BLEEDSIM_MEMBER(P, dicrotic), "", {0, 1},
        "a₂: the swing at twice the heart rate (the dicrotic shoulder)"},
       {"arterial_density", T::number, BLEEDSIM_MEMBER(P, arterial_density), "", {0, 1},
        "with [vessels]: a wound whose mean vessel density reaches this is arterial (cuts may also say so)"}},
      {{"systolic + dicrotic < 1 and dicrotic < systolic: the flow never stops, and the beat dominates",
        flow_stays_forward},
       {"the scene has [particles], and (1 + systolic + dicrotic) × |velocity_mm_s| + √2 × velocity_jitter_mm_s is "
        "within particles.max_speed_mm_s",
        spurt_within_speed_limit}}};
  return table;
}

const Effect<PulseParams>& pulse_effect() {
  static const Effect<PulseParams> row = [] {
    Effect<PulseParams> e{pulse_table};
    e.describe = describe_pulse;
    return e;
  }();
  return row;
}

}  // namespace bleedsim
