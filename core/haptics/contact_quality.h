#pragma once
// The force's quality contact by contact over a run of the haptic loop (docs/haptics.md, "Force
// quality"): the ticks are cut into contacts, and each contact is measured by the formulas of
// core/haptics/force_quality.h. A contact is a maximal run of consecutive ticks with the tip in
// contact (HapticTick::contact): it begins on a tick in contact after one out of it (or on tick 0)
// and ends on the last tick in contact before one out of it, or at the run's last tick.
//
// Fed tick by tick, as the run makes them; it keeps the ticks of the contact under way only, and one
// number per tick (the energy margin) for the plot.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "core/haptics/force_quality.h"
#include "core/haptics/haptics.h"

namespace bleedsim {

struct ContactQuality {
  std::int64_t first_tick = 0, last_tick = 0;  // in contact from the one to the other, both included
  bool released = true;                         // false: the run ended in this contact
  double max_penetration_m = 0;
  double peak_force_N = 0;
  Metric rise_time_s;
  ForceRate force_rate;
  Oscillation oscillation;                      // above kHandCutoff_hz
  double overshoot_N = 0;
  double margin_end_J = 0;                      // D − W over the contact
  Metric worst_margin_J;                        // its least value ...
  std::int64_t worst_margin_tick = 0;           // ... and the tick whose hold gave it
  std::int64_t ticks_at_force_limit = 0;

  std::int64_t ticks() const { return last_tick - first_tick + 1; }
};

// The metrics this contact lacks, each by its name in the run's file (docs/output-format.md) with why.
std::vector<std::pair<std::string, std::string>> unavailable_metrics(const ContactQuality& contact);

class ContactQualityMeter {
 public:
  // The contact's spring k, the force cap and the device's damping B, from the scene's [haptics].
  explicit ContactQualityMeter(const HapticParams& params);

  // The next tick of the run (tick numbers must follow one another from 0).
  void add(const HapticTick& tick);
  // Ends a contact still under way (the run ended in it); call once, after the last tick.
  void finish();

  const std::vector<ContactQuality>& contacts() const { return contacts_; }
  // Every tick's passivity margin M (force_quality.h): the contact's D − W through the tick's hold,
  // 0 out of contact (and on a last tick whose hold the run did not complete: its M before).
  const std::vector<double>& margin_J() const { return margin_J_; }
  const HapticParams& params() const { return params_; }

 private:
  void close_contact(bool released, const Eigen::Vector3d* position_after);

  HapticParams params_;
  std::int64_t ticks_ = 0;
  // The contact under way: its ticks' positions, forces and depths.
  std::int64_t first_tick_ = -1;  // −1: none
  std::vector<Eigen::Vector3d> position_m_, force_N_;
  std::vector<double> force_norm_N_, penetration_m_;
  std::vector<ContactQuality> contacts_;
  std::vector<double> margin_J_;
};

}  // namespace bleedsim
