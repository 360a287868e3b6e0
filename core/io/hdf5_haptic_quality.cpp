#include "core/io/hdf5_haptic_quality.h"

#include <cstdint>
#include <vector>

#include "core/io/hdf5_objects.h"

namespace bleedsim {
namespace {

// Each metric a contact lacks, "metric: why", joined by "; ".
std::string unavailable(const ContactQuality& c) {
  std::string text;
  for (const auto& [name, why] : unavailable_metrics(c)) text += (text.empty() ? "" : "; ") + name + ": " + why;
  return text;
}

void write_group(const Hdf5Objects& h5, hid_t haptics, const ContactQualityMeter& meter) {
  const Hdf5Objects::Group group = h5.group(haptics, "quality");
  const hid_t g = group.get();
  h5.text(g, "description", "the force's quality, one row per contact (docs/haptics.md, \"Force quality\")");
  const HapticParams& p = meter.params();
  h5.number(g, "cutoff_hz", kHandCutoff_hz);
  h5.number(g, "stiffness_N_per_m", p.stiffness_N_per_m);
  h5.number(g, "max_force_N", p.max_force_N);
  h5.number(g, "device_damping_Ns_per_m", p.device_damping_Ns_per_m);

  std::vector<std::int64_t> first, last, released, worst_tick, at_cap;
  std::vector<double> depth, peak, rise, rates, rms, share, overshoot, end, worst;
  std::vector<std::string> why;
  for (const ContactQuality& c : meter.contacts()) {
    first.push_back(c.first_tick);
    last.push_back(c.last_tick);
    released.push_back(c.released);
    depth.push_back(c.max_penetration_m);
    peak.push_back(c.peak_force_N);
    rise.push_back(c.rise_time_s.value);
    rates.insert(rates.end(), {c.force_rate.p50_N_per_s, c.force_rate.p99_N_per_s, c.force_rate.max_N_per_s});
    rms.push_back(c.oscillation.rms_above_N.value);
    share.push_back(c.oscillation.share_above.value);
    overshoot.push_back(c.overshoot_N);
    end.push_back(c.margin_end_J);
    worst.push_back(c.worst_margin_J.value);
    worst_tick.push_back(c.worst_margin_tick);
    at_cap.push_back(c.ticks_at_force_limit);
    why.push_back(unavailable(c));
  }
  h5.integers(g, "first_tick", first);
  h5.integers(g, "last_tick", last);
  h5.integers(g, "released", released);
  h5.numbers(g, "max_penetration", depth, 0, "m");
  h5.numbers(g, "peak_force", peak, 0, "N");
  h5.numbers(g, "rise_time", rise, 0, "s");
  h5.numbers(g, "force_rate", rates, 3, "N/s");
  h5.numbers(g, "oscillation_rms", rms, 0, "N");
  h5.numbers(g, "oscillation_share", share);
  h5.numbers(g, "overshoot", overshoot, 0, "N");
  h5.numbers(g, "margin_end", end, 0, "J");
  h5.numbers(g, "worst_margin", worst, 0, "J");
  h5.integers(g, "worst_margin_tick", worst_tick);
  h5.integers(g, "ticks_at_force_limit", at_cap);
  h5.texts(g, "unavailable", why);
  h5.numbers(g, "margin", meter.margin_J(), 0, "J");
}

}  // namespace

void write_haptic_quality(const std::string& path, const ContactQualityMeter& meter) {
  const Hdf5Objects h5(path);
  Hdf5Handle<H5Fclose> file{h5.check(H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), "open the file")};
  {
    const Hdf5Handle<H5Gclose> haptics{h5.check(H5Gopen2(file.get(), "haptics", H5P_DEFAULT), "open group /haptics")};
    write_group(h5, haptics.get(), meter);
  }
  // HDF5 writes much of what was added as it closes the file: a full disk shows here.
  if (file.close() < 0) h5.check.fail("close the file");
}

}  // namespace bleedsim
