#pragma once
// The heartbeat (docs/bleeding.md, "Pulse"): an arterial wound's flow and exit speed follow the
// waveform w(t) = 1 + a₁ sin(2πft) + a₂ sin(4πft), whose mean over a beat is exactly 1, so the
// mean flow is the wound's stated flow; venous wounds ooze at it steadily.

namespace bleedsim {

struct Heartbeat {
  double heart_rate_per_min = 72.0;
  double systolic = 0.6;  // a₁: the beat's share of the flow, at the heart rate
  double dicrotic = 0.3;  // a₂: the shoulder after it, at twice the heart rate
};

// w(t): the flow relative to its mean at time t of the scene (the heart beats from t = 0).
double pulse_waveform(const Heartbeat& beat, double t_s);

// ∫ e^{−(t − t₀)/τ} w(t) dt over [t₀, t₀ + s], in closed form (τ = 0: no clotting, the exponential
// is 1): the blood of an arterial wound opened at t₀, per unit of its starting flow.
double pulsed_flowing_s(const Heartbeat& beat, double opened_s, double bleeding_s, double clot_s);

}  // namespace bleedsim
