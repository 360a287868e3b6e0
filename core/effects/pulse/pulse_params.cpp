#include "core/effects/pulse/pulse_params.h"

#include <cmath>

#include "core/runtime/message_text.h"
#include "core/scene/scene.h"

namespace bleedsim {
namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;

double angular_rate(const PulseParams& p) { return kTwoPi * p.heart_rate_per_min / 60.0; }

// ∫ e^{−ku} sin(ωu + φ) du over [0, s] = [k sin φ + ω cos φ − e^{−ks}(k sin(ωs + φ) + ω cos(ωs + φ))] / (k² + ω²).
double damped_sine_integral(double k, double omega, double phase, double s) {
  const double decay = std::exp(-k * s), end = omega * s + phase;
  return (k * std::sin(phase) + omega * std::cos(phase) - decay * (k * std::sin(end) + omega * std::cos(end))) /
         (k * k + omega * omega);
}

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
  if (!scene.particles) return {"heart_rate_per_min", "has no effect: this scene declares no [particles]"};
  const ParticleParams& q = *scene.particles;
  const double fastest =
      (1.0 + p.systolic + p.dicrotic) * std::hypot(q.velocity_x_mm_s, q.velocity_y_mm_s) +
      std::sqrt(2.0) * q.velocity_jitter_mm_s;
  if (fastest <= q.max_speed_mm_s) return {};
  return {"systolic", "makes an arterial spurt of up to " + format_number(fastest) +
                          " mm/s ((1 + systolic + dicrotic) × |particles.velocity_mm_s| + √2 × velocity_jitter_mm_s), "
                          "past particles.max_speed_mm_s = " + format_number(q.max_speed_mm_s)};
}

}  // namespace

double pulse_waveform(const PulseParams& p, double t_s) {
  const double theta = angular_rate(p) * t_s;
  return 1.0 + p.systolic * std::sin(theta) + p.dicrotic * std::sin(2.0 * theta);
}

double pulsed_flowing_s(const PulseParams& p, double opened_s, double bleeding_s, double clot_s) {
  const double k = clot_s > 0.0 ? 1.0 / clot_s : 0.0, omega = angular_rate(p);
  const double steady = clot_s > 0.0 ? clot_s * -std::expm1(-bleeding_s / clot_s) : bleeding_s;
  return steady + p.systolic * damped_sine_integral(k, omega, omega * opened_s, bleeding_s) +
         p.dicrotic * damped_sine_integral(k, 2.0 * omega, 2.0 * omega * opened_s, bleeding_s);
}

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

}  // namespace bleedsim
