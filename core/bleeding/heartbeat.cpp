#include "core/bleeding/heartbeat.h"

#include <cmath>

namespace bleedsim {
namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;

double angular_rate(const Heartbeat& beat) { return kTwoPi * beat.heart_rate_per_min / 60.0; }

// ∫ e^{−ku} sin(ωu + φ) du over [0, s] = [k sin φ + ω cos φ − e^{−ks}(k sin(ωs + φ) + ω cos(ωs + φ))] / (k² + ω²).
double damped_sine_integral(double k, double omega, double phase, double s) {
  const double decay = std::exp(-k * s), end = omega * s + phase;
  return (k * std::sin(phase) + omega * std::cos(phase) - decay * (k * std::sin(end) + omega * std::cos(end))) /
         (k * k + omega * omega);
}

}  // namespace

double pulse_waveform(const Heartbeat& beat, double t_s) {
  const double theta = angular_rate(beat) * t_s;
  return 1.0 + beat.systolic * std::sin(theta) + beat.dicrotic * std::sin(2.0 * theta);
}

double pulsed_flowing_s(const Heartbeat& beat, double opened_s, double bleeding_s, double clot_s) {
  const double k = clot_s > 0.0 ? 1.0 / clot_s : 0.0, omega = angular_rate(beat);
  const double steady = clot_s > 0.0 ? clot_s * -std::expm1(-bleeding_s / clot_s) : bleeding_s;
  return steady + beat.systolic * damped_sine_integral(k, omega, omega * opened_s, bleeding_s) +
         beat.dicrotic * damped_sine_integral(k, 2.0 * omega, 2.0 * omega * opened_s, bleeding_s);
}

}  // namespace bleedsim
