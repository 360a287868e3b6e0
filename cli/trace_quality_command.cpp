// bleedsim trace quality: the force a scenario's trace renders, contact by contact (docs/haptics.md,
// "Force quality"). A trace holds the stylus' motion only: the force comes from the scene — its
// surface or mesh, its spring, damper and cap — so the command takes scenarios, each replaying its
// trace through the haptic loop over the ticks a run of it plays (the same numbers as the run's
// /haptics/quality).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "core/haptics/contact_quality.h"
#include "core/haptics/haptic_params.h"
#include "core/haptics/haptics.h"
#include "core/haptics/trace_replay.h"
#include "core/io/scenario.h"
#include "core/runtime/message_text.h"

namespace bleedsim::cli {
namespace {

// The loop replayed over the run's ticks, every tick measured.
ContactQualityMeter replay_quality(const Scene& scene) {
  HapticLoop loop(scene);
  ContactQualityMeter meter(*scene.haptics);
  const std::int64_t ticks = scene.haptic_ticks_through_frame(scene.frame_count() - 1);
  for (std::int64_t n = 0; n < ticks; ++n) meter.add(loop.tick(trace_sample_at_tick(*scene.trace, n)).record);
  meter.finish();
  return meter;
}

// A metric `width` wide: `scale` times its value with `decimals`, or "n/a".
std::string cell(const Metric& metric, double scale, int decimals, int width) {
  char text[64];
  if (metric.available()) std::snprintf(text, sizeof text, "%*.*f", width, decimals, scale * metric.value);
  else std::snprintf(text, sizeof text, "%*s", width, "n/a");
  return text;
}

// One row of the table: mm, ms, mN and mJ, a contact the run ends in marked '*'.
void print_contact(int number, const ContactQuality& c) {
  char worst_at[32] = "";
  if (c.worst_margin_J.available())
    std::snprintf(worst_at, sizeof worst_at, "%.3f", double(c.worst_margin_tick) / kHapticRate_hz);
  std::printf("  %3d  %7.3f-%-7.3f%s %6lld %6.2f %6.3f %s %8.1f %8.1f %8.1f %s %s %8.2f %8.3f %s %-8s %6lld\n", number,
              double(c.first_tick) / kHapticRate_hz, double(c.last_tick) / kHapticRate_hz, c.released ? " " : "*",
              static_cast<long long>(c.ticks()), 1000.0 * c.max_penetration_m, c.peak_force_N,
              cell(c.rise_time_s, 1000.0, 1, 6).c_str(), c.force_rate.p50_N_per_s, c.force_rate.p99_N_per_s,
              c.force_rate.max_N_per_s, cell(c.oscillation.rms_above_N, 1000.0, 3, 7).c_str(),
              cell(c.oscillation.share_above, 100.0, 2, 6).c_str(), 1000.0 * c.overshoot_N, 1000.0 * c.margin_end_J,
              cell(c.worst_margin_J, 1000.0, 3, 8).c_str(), worst_at, static_cast<long long>(c.ticks_at_force_limit));
}

// Why a contact lacks a metric, one line each.
void print_unavailable(int number, const ContactQuality& c) {
  for (const auto& [name, why] : unavailable_metrics(c)) std::printf("  contact %d, %s: %s\n", number, name.c_str(), why.c_str());
}

void report(const Scenario& file, const ContactQualityMeter& meter) {
  const Scene& scene = file.scene;
  const HapticParams& h = *scene.haptics;
  const std::int64_t ticks = std::int64_t(meter.margin_J().size());
  std::printf("%s: %s replays %s: %lld ticks (%.3f s)\n", file.path.c_str(), scene.name.c_str(),
              scene.trace->path.c_str(), static_cast<long long>(ticks), double(ticks - 1) / kHapticRate_hz);
  std::printf("  %s; k %g N/m, b %g N·s/m, cap %g N; device damping B %g N·s/m (k·T/2 + |b| = %g); "
              "oscillation above %g Hz\n",
              scene.mesh ? "tissue mesh" : ("surface z = " + format_number(h.surface_z_mm) + " mm").c_str(),
              h.stiffness_N_per_m, h.damping_Ns_per_m, h.max_force_N, h.device_damping_Ns_per_m,
              passivity_demand_Ns_per_m(h), kHandCutoff_hz);
  const std::vector<ContactQuality>& contacts = meter.contacts();
  if (contacts.empty()) {
    std::printf("  no contact: the stylus never touches the tissue\n");
    return;
  }
  std::printf("  %3s  %-16s %6s %6s %6s %6s %26s %14s %7s %8s %17s %6s\n", "", "in contact", "", "depth", "peak",
              "rise", "force rate dF/dt, N/s", "above 30 Hz", "over-", "D-W, mJ", "", "at");
  std::printf("  %3s  %-16s %6s %6s %6s %6s %8s %8s %8s %7s %6s %7s %8s %17s %6s\n", "#", "from-to, s", "ticks", "mm",
              "N", "ms", "p50", "p99", "max", "rms mN", "share%", "shoot mN", "end", "worst @ s", "cap");
  double worst = 0;
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    print_contact(int(i) + 1, contacts[i]);
    if (contacts[i].worst_margin_J.available()) worst = std::min(worst, contacts[i].worst_margin_J.value);
  }
  for (std::size_t i = 0; i < contacts.size(); ++i) print_unavailable(int(i) + 1, contacts[i]);
  if (!contacts.back().released) std::printf("  * the run ends in this contact: its release is not measured\n");
  std::printf(worst >= 0 ? "  passive: D - W >= 0 at every tick of every contact\n"
                         : "  ACTIVE: D - W falls to %.3g mJ: the rendering injects energy\n",
              1000.0 * worst);
}

}  // namespace

int trace_quality_command(const std::vector<std::string>& scenarios, const std::vector<std::string>& overrides) {
  for (const std::string& path : scenarios) {
    const Scenario file = load_scenario(path, ReadTissue::header_only, overrides);
    if (!file.scene.trace)
      throw InputError(SourcePlace{path, 0, 0}, "haptics",
                       "the scenario replays no trace: trace quality needs a [haptics] table with a trace");
    if (&path != &scenarios.front()) std::printf("\n");
    report(file, replay_quality(file.scene));
  }
  return 0;
}

}  // namespace bleedsim::cli
