#include "core/study/study_output.h"

#include <hdf5.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <stdexcept>

#include "core/io/hdf5_objects.h"
#include "core/runtime/message_text.h"

namespace bleedsim {
namespace {

std::string cell(double v) {
  if (std::isnan(v)) return "";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return format_significant(v, 6);
}

// A CSV field: quoted when it holds a comma, a quote or a line break.
std::string field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string cells(const Estimate& e) { return cell(e.value) + ',' + cell(e.lo) + ',' + cell(e.hi); }

std::string with_bounds(const std::string& name) { return name + ',' + name + "_lo," + name + "_hi"; }

void rename_into_place(const std::string& partial, const std::string& path) {
  std::error_code error;
  std::filesystem::rename(partial, path, error);
  if (error) throw std::runtime_error("cannot rename '" + partial + "' to '" + path + "': " + error.message());
}

// A file that failed part way is nobody's output: it goes, so no half-written file stays behind.
void remove_partial(const std::string& partial) {
  std::error_code ignored;  // the failure being reported matters more than this one
  std::filesystem::remove(partial, ignored);
}

// Writes `path` through `write` into a temporary file, renamed into place once it is whole.
void write_text_file(const std::string& path, const std::function<void(std::ostream&)>& write) {
  const std::string partial = path + ".partial";
  std::ofstream out(partial);
  if (out) write(out);
  if (out) out.close();
  if (!out) {
    const int reason = errno;  // the failed open, write or close's (EFBIG, ENOSPC)
    remove_partial(partial);
    throw std::runtime_error("cannot write '" + partial + "': " + std::strerror(reason));
  }
  rename_into_place(partial, path);
}

const char* kRunColumns[] = {"film_l1_mm", "film_l2_mm", "frame_psnr_db", "stain_l1"};

std::string run_cells(const RunDistances& d) {
  return cells(d.film_l1_mm) + ',' + cells(d.film_l2_mm) + ',' + cells(d.frame_psnr_db) + ',' + cells(d.stain_l1);
}

// The last seed to come to rest (issue 36 holds every seed to its bound, not the mean); NaN where
// the setting has no rest time.
double latest_rest_s(const SettingResult& s) {
  for (std::size_t m = 0; m < metrics().size(); ++m)
    if (metrics()[m].metric == Metric::rest && !s.per_seed[m].empty())
      return *std::max_element(s.per_seed[m].begin(), s.per_seed[m].end());
  return kNaN;
}

std::string describe_value(const StudySetting& s) {
  return s.role == "reference" || s.role == "scene" || s.role == "noise_floor" ? "" : cell(s.value);
}

// ---- HDF5 -------------------------------------------------------------------------------------

using Group = Hdf5Objects::Group;

// Estimates as rows of (value, lo, hi).
void estimates(const Hdf5Objects& h5, hid_t group, const std::string& name, const std::vector<Estimate>& rows,
               const std::string& unit = "") {
  std::vector<double> values;
  for (const Estimate& e : rows) values.insert(values.end(), {e.value, e.lo, e.hi});
  h5.numbers(group, name, values, 3, unit);
}

std::string numbered(std::size_t i) {
  char name[32];
  std::snprintf(name, sizeof name, "%03zu", i);
  return name;
}

std::vector<Estimate> rms_of(const std::vector<Distance>& distances) {
  std::vector<Estimate> out;
  for (const Distance& d : distances) out.push_back(d.rms);
  return out;
}

void write_setting(const Hdf5Objects& h5, hid_t group, const SettingResult& s) {
  h5.text(group, "knob", s.setting.knob);
  h5.text(group, "value", describe_value(s.setting));
  h5.text(group, "role", s.setting.role);
  h5.text(group, "status", s.status);
  if (s.status != "ok") return;
  for (std::size_t m = 0; m < metrics().size(); ++m) {
    const MetricInfo& info = metrics()[m];
    if (std::isnan(s.value[m].value)) continue;
    estimates(h5, group, info.name, {s.value[m]}, info.unit);
    h5.numbers(group, std::string(info.name) + "_per_seed", s.per_seed[m], 0, info.unit);
    estimates(h5, group, std::string(info.name) + "_distance", {s.distance[m].rms}, info.unit);
    if (!s.curves[m].empty()) estimates(h5, group, std::string(info.name) + "_per_frame", s.curves[m], info.unit);
  }
  if (!s.pile_profile_mm.empty()) estimates(h5, group, "pile_profile_mm", s.pile_profile_mm, "mm");
  const RunDistances& d = s.against_reference;
  estimates(h5, group, "against_reference", {d.film_l1_mm, d.film_l2_mm, d.frame_psnr_db, d.stain_l1});
  h5.text(group, "against_reference_rows", "film_l1_mm, film_l2_mm, frame_psnr_db, stain_l1");
}

void write_ladder(const Hdf5Objects& h5, hid_t group, const LadderResult& ladder, const KnobCheck& check) {
  const Knob& knob = *find_knob(ladder.knob);
  h5.text(group, "changes", knob.trades);
  h5.text(group, "holds", knob.holds);
  h5.numbers(group, "values", ladder.values);
  std::string roles, refused;
  for (const std::string& r : ladder.roles) roles += (roles.empty() ? "" : ", ") + r;
  for (const auto& [value, why] : ladder.refused) refused += (refused.empty() ? "" : "; ") + format_number(value) + ": " + why;
  h5.text(group, "roles", roles);
  h5.text(group, "refused", refused);
  h5.text(group, "check", check.status);
  for (std::size_t m = 0; m < metrics().size(); ++m) {
    const LadderMetric& lm = ladder.per_metric[m];
    if (lm.level_values.empty()) continue;
    const Group metric = h5.group(group, metrics()[m].name);
    estimates(h5, metric.get(), "level_values", lm.level_values, metrics()[m].unit);
    estimates(h5, metric.get(), "differences", rms_of(lm.fit.differences), metrics()[m].unit);
    estimates(h5, metric.get(), "orders", lm.fit.orders);
    h5.text(metric.get(), "statement", lm.fit.statement);
    h5.numbers(metric.get(), "asymptotic_from", {double(lm.fit.asymptotic_from)});
    estimates(h5, metric.get(), "extrapolated", {lm.extrapolated}, metrics()[m].unit);
    estimates(h5, metric.get(), "limit_distance", {lm.limit_distance}, metrics()[m].unit);
  }
}

}  // namespace

void write_study_csv(const std::string& path, const Study& study, const StudyResult& result) {
  write_text_file(path, [&](std::ostream& out) {
    out << "scene,knob,value,role,backend,status,seeds";
    for (const char* column : kRunColumns) out << ',' << with_bounds(column);
    for (const MetricInfo& info : metrics()) out << ',' << with_bounds(info.name) << ',' << with_bounds(std::string(info.name) + "_dist");
    // New columns go last, so that a reader counting columns keeps finding the older ones.
    out << ",check,time_ms_p50,time_ms_p99,time_ms_p50_lo,time_ms_p50_hi,rest_s_latest_seed\n";
    const std::string scene = field(study.scene().name), seeds = std::to_string(study.seeds());
    for (std::size_t i = 0; i < result.settings.size(); ++i) {
      const SettingResult& s = result.settings[i];
      std::string check;
      if (s.setting.role == "reference") check = result.check.verdict;
      for (std::size_t l = 0; l < study.ladders().size(); ++l)
        if (study.ladders()[l].refined && study.ladders()[l].settings.back() == i) check = result.check.knobs[l].status;
      for (const SettingTiming& t : s.timing) {
        out << scene << ',' << s.setting.knob << ',' << describe_value(s.setting) << ',' << s.setting.role << ','
            << to_string(t.backend) << ',' << field(s.status) << ',' << seeds << ',' << run_cells(s.against_reference);
        for (std::size_t m = 0; m < metrics().size(); ++m) out << ',' << cells(s.value[m]) << ',' << cells(s.distance[m].rms);
        out << ',' << field(check) << ',' << cell(t.ms_p50) << ',' << cell(t.ms_p99) << ',' << cell(t.ms_p50_low) << ','
            << cell(t.ms_p50_high) << ',' << cell(latest_rest_s(s)) << '\n';
      }
    }
    // The noise floor: two reference runs of different seeds (the single-run columns), and one run's
    // seed spread (the distance columns).
    out << scene << ",reference,,noise_floor,,ok," << seeds << ',' << run_cells(result.noise_floor);
    for (std::size_t m = 0; m < metrics().size(); ++m) out << ",,,," << cells(result.seed_spread[m]);
    out << ",,,,,,\n";
  });
}

void write_ladders_csv(const std::string& path, const StudyResult& result) {
  write_text_file(path, [&](std::ostream& out) {
    out << "knob,metric,unit,level,value,role,status," << with_bounds("mean") << ',' << with_bounds("difference") << ','
        << with_bounds("order") << ",asymptotic,statement," << with_bounds("extrapolated") << ','
        << with_bounds("limit_distance") << ",seed_spread,check\n";
    for (std::size_t l = 0; l < result.ladders.size(); ++l) {
      const LadderResult& ladder = result.ladders[l];
      const std::string check = field(result.check.knobs[l].status);
      for (std::size_t m = 0; m < metrics().size(); ++m) {
        const LadderMetric& lm = ladder.per_metric[m];
        if (lm.level_values.empty()) continue;
        const std::string start = ladder.knob + ',' + metrics()[m].name + ',' + metrics()[m].unit + ',';
        const std::string tail = ',' + field(lm.fit.statement) + ',' + cells(lm.extrapolated) + ',' +
                                 cells(lm.limit_distance) + ',' + cell(result.seed_spread[m].value) + ',' + check + '\n';
        for (std::size_t k = 0; k < ladder.values.size(); ++k) {
          out << start << k << ',' << cell(ladder.values[k]) << ',' << ladder.roles[k] << ",ok," << cells(lm.level_values[k])
              << ',' << (k >= 1 ? cells(lm.fit.differences[k - 1].rms) : ",,") << ','
              << (k >= 2 ? cells(lm.fit.orders[k - 2]) : ",,") << ','
              << (lm.fit.asymptotic_from >= 0 && int(k) >= lm.fit.asymptotic_from ? "yes" : "no") << tail;
        }
        for (const auto& [value, why] : ladder.refused)
          out << start << ',' << cell(value) << ",," << field(why) << ",,,,,,,,,," << tail;
      }
    }
  });
}

void write_study_hdf5(const std::string& path, const Study& study, const StudyResult& result,
                      const std::vector<std::pair<std::string, std::string>>& attributes) {
  const std::string partial = path + ".partial";
  const Hdf5Objects h5(partial);
  Hdf5Handle<H5Fclose> handle{h5.check(H5Fcreate(partial.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), "create the file")};
  const hid_t file = handle.get();
  // Every object in the file is closed when this block ends, so the file really closes with it.
  try {
    for (const auto& [name, value] : attributes) h5.text(file, name, value);
    h5.text(file, "reference", study.reference_description());
    h5.text(file, "grid", std::to_string(study.grid_width()) + " x " + std::to_string(study.grid_height()));
    h5.text(file, "seeds", std::to_string(study.seeds()) + " (the scene's seed " + std::to_string(study.seed_of(0)) +
                               " and the next ones)");
    h5.text(file, "verdict", result.check.verdict);
    h5.text(file, "accepted", result.check.accepted ? "yes" : "no");
    std::vector<double> times, snapshots;
    for (int k = 0; k < study.frames_per_run(); ++k) times.push_back(study.scene().frame_time_s(k));
    for (const int k : study.snapshot_frames()) snapshots.push_back(k);
    h5.numbers(file, "frame_time_s", times, 0, "s");
    h5.numbers(file, "panel_mm", {study.scene().domain.width_mm, study.scene().domain.height_mm}, 0, "mm");
    h5.numbers(file, "snapshot_frames", snapshots);

    const Group floor = h5.group(file, "noise_floor");
    const RunDistances& d = result.noise_floor;
    estimates(h5, floor.get(), "between_seeds", {d.film_l1_mm, d.film_l2_mm, d.frame_psnr_db, d.stain_l1});
    h5.text(floor.get(), "between_seeds_rows", "film_l1_mm, film_l2_mm, frame_psnr_db, stain_l1");
    for (std::size_t m = 0; m < metrics().size(); ++m)
      if (!std::isnan(result.seed_spread[m].value))
        estimates(h5, floor.get(), std::string(metrics()[m].name) + "_seed_spread", {result.seed_spread[m]}, metrics()[m].unit);

    const Group settings = h5.group(file, "settings");
    for (std::size_t i = 0; i < result.settings.size(); ++i) {
      const Group group = h5.group(settings.get(), numbered(i));
      write_setting(h5, group.get(), result.settings[i]);
    }

    const Group ladders = h5.group(file, "ladders");
    for (std::size_t l = 0; l < result.ladders.size(); ++l) {
      const Group group = h5.group(ladders.get(), result.ladders[l].knob);
      write_ladder(h5, group.get(), result.ladders[l], result.check.knobs[l]);
    }

    const Group timing = h5.group(file, "timing");
    for (std::size_t i = 0; i < result.settings.size(); ++i) {
      const Group group = h5.group(timing.get(), numbered(i));
      for (const SettingTiming& t : result.settings[i].timing) {
        if (t.frame_seconds.empty()) continue;
        const Group backend = h5.group(group.get(), to_string(t.backend));
        std::vector<double> seconds;
        for (const std::vector<double>& seed : t.frame_seconds) seconds.insert(seconds.end(), seed.begin(), seed.end());
        h5.numbers(backend.get(), "frame_seconds", seconds, t.frame_seconds.front().size(), "s");
        h5.text(backend.get(), "device", t.device);
        h5.numbers(backend.get(), "ms_p50_p99_seedmin_seedmax", {t.ms_p50, t.ms_p99, t.ms_p50_low, t.ms_p50_high}, 0, "ms");
      }
    }
  } catch (...) {
    handle.close();
    remove_partial(partial);
    throw;
  }
  // HDF5 writes most of the file as it closes it: a full disk or a file size limit shows here.
  if (handle.close() < 0) {
    remove_partial(partial);
    h5.check.fail("close the file");
  }
  rename_into_place(partial, path);
}

void write_study_files(const std::string& folder, const Study& study, const StudyResult& result,
                       const std::vector<std::pair<std::string, std::string>>& attributes) {
  const std::filesystem::path dir(folder);
  write_study_csv((dir / "study.csv").string(), study, result);
  write_ladders_csv((dir / "ladders.csv").string(), result);
  write_study_hdf5((dir / "study.h5").string(), study, result, attributes);
}

}  // namespace bleedsim
