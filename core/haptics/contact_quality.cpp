#include "core/haptics/contact_quality.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace bleedsim {

std::vector<std::pair<std::string, std::string>> unavailable_metrics(const ContactQuality& c) {
  std::vector<std::pair<std::string, std::string>> missing;
  const std::pair<const char*, const Metric*> metrics[] = {{"rise_time", &c.rise_time_s},
                                                          {"oscillation_rms", &c.oscillation.rms_above_N},
                                                          {"oscillation_share", &c.oscillation.share_above},
                                                          {"worst_margin", &c.worst_margin_J}};
  for (const auto& [name, metric] : metrics)
    if (!metric->available()) missing.emplace_back(name, metric->unavailable);
  return missing;
}

ContactQualityMeter::ContactQualityMeter(const HapticParams& params) : params_(params) {}

void ContactQualityMeter::add(const HapticTick& tick) {
  if (tick.tick != ticks_)
    throw std::invalid_argument("ContactQualityMeter: tick " + std::to_string(tick.tick) + " given after " +
                                std::to_string(ticks_) + " ticks");
  ++ticks_;
  margin_J_.push_back(0.0);
  if (!tick.contact) {
    if (first_tick_ >= 0) close_contact(true, &tick.tool_m);
    return;
  }
  if (first_tick_ < 0) first_tick_ = tick.tick;
  position_m_.push_back(tick.tool_m);
  force_N_.push_back(tick.force_N);
  force_norm_N_.push_back(tick.force_N.norm());
  penetration_m_.push_back(tick.penetration_m);
}

void ContactQualityMeter::finish() {
  if (first_tick_ >= 0) close_contact(false, nullptr);
}

void ContactQualityMeter::close_contact(bool released, const Eigen::Vector3d* position_after) {
  ContactQuality q;
  q.first_tick = first_tick_;
  q.last_tick = first_tick_ + std::int64_t(force_N_.size()) - 1;
  q.released = released;
  q.max_penetration_m = *std::max_element(penetration_m_.begin(), penetration_m_.end());
  q.peak_force_N = *std::max_element(force_norm_N_.begin(), force_norm_N_.end());
  q.rise_time_s = rise_time_s(force_norm_N_, kHapticPeriod_s);
  q.force_rate = force_rate(force_N_, released, kHapticPeriod_s);
  q.oscillation = oscillation(force_norm_N_, kHandCutoff_hz, kHapticPeriod_s);
  q.overshoot_N = overshoot_N(force_norm_N_, penetration_m_, params_.stiffness_N_per_m);
  if (position_after) position_m_.push_back(*position_after);  // the last tick's hold ends there
  const EnergyMargin margin = energy_margin(position_m_, force_N_, params_.device_damping_Ns_per_m, kHapticPeriod_s);
  q.margin_end_J = margin.end_J;
  q.worst_margin_J = margin.worst_J;
  q.worst_margin_tick = first_tick_ + std::int64_t(margin.worst_tick);
  q.ticks_at_force_limit = ticks_at_force_limit(force_norm_N_, params_.max_force_N);
  for (std::size_t j = 0; j < force_N_.size(); ++j)
    margin_J_[std::size_t(first_tick_) + j] =
        margin.after_tick_J.empty() ? 0.0 : margin.after_tick_J[std::min(j, margin.after_tick_J.size() - 1)];
  contacts_.push_back(std::move(q));
  first_tick_ = -1;
  position_m_.clear();
  force_N_.clear();
  force_norm_N_.clear();
  penetration_m_.clear();
}

}  // namespace bleedsim
