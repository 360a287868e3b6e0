#include "core/study/study_output.h"

#include <hdf5.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <stdexcept>

#include "core/runtime/message_text.h"
#include "core/runtime/timing_summary.h"

namespace bleedsim {
namespace {

// The per-frame errors by name, as the CSV columns and the HDF5 datasets call them.
struct ErrorColumn {
  const char* name;
  double FrameErrors::*member;
  const char* unit;
};
const ErrorColumn kErrorColumns[] = {{"film_l1_mm", &FrameErrors::film_l1_mm, "mm"},
                                     {"film_l2_mm", &FrameErrors::film_l2_mm, "mm"},
                                     {"frame_mse", &FrameErrors::frame_mse, "(8-bit levels)^2"},
                                     {"covered_area_rel_error", &FrameErrors::covered_area_rel_error, "1"},
                                     {"volume_rel_error", &FrameErrors::volume_rel_error, "1"},
                                     {"pile_height_error_mm", &FrameErrors::pile_height_error_mm, "mm"},
                                     {"stain_l1", &FrameErrors::stain_l1, "1"}};

std::string cell(double v) {
  if (std::isnan(v)) return "";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return format_significant(v, 6);
}

// A CSV field: quoted when it holds a comma or a quote.
std::string field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

void rename_into_place(const std::string& partial, const std::string& path) {
  std::error_code error;
  std::filesystem::rename(partial, path, error);
  if (error) throw std::runtime_error("cannot rename '" + partial + "' to '" + path + "': " + error.message());
}

// HDF5 handles closed on every path out, errors as exceptions naming the file.
struct H5 {
  std::string file;
  hid_t check(hid_t id, const std::string& what) const {
    if (id < 0) throw std::runtime_error("cannot " + what + " in HDF5 file '" + file + "'");
    return id;
  }
};

void text_attribute(const H5& h5, hid_t object, const std::string& name, const std::string& value) {
  const hid_t type = h5.check(H5Tcopy(H5T_C_S1), "copy the string type");
  H5Tset_size(type, H5T_VARIABLE);
  H5Tset_cset(type, H5T_CSET_UTF8);
  const hid_t space = h5.check(H5Screate(H5S_SCALAR), "create a dataspace");
  const hid_t attribute = h5.check(H5Acreate2(object, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT),
                                   "create attribute " + name);
  const char* text = value.c_str();
  const herr_t written = H5Awrite(attribute, type, &text);
  H5Aclose(attribute);
  H5Sclose(space);
  H5Tclose(type);
  h5.check(written, "write attribute " + name);
}

void number_dataset(const H5& h5, hid_t group, const std::string& name, const std::vector<double>& values,
                    const std::string& unit) {
  const hsize_t n = values.size();
  const hid_t space = h5.check(H5Screate_simple(1, &n, nullptr), "create a dataspace");
  const hid_t set = h5.check(H5Dcreate2(group, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                             "create dataset " + name);
  const herr_t written = H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
  text_attribute(h5, set, "unit", unit);
  H5Dclose(set);
  H5Sclose(space);
  h5.check(written, "write dataset " + name);
}

FrameErrors mean_over_frames(const std::vector<FrameErrors>& errors) {
  FrameErrors mean;
  for (const ErrorColumn& column : kErrorColumns) {
    double sum = 0;
    for (const FrameErrors& e : errors) sum += e.*column.member;
    mean.*column.member = errors.empty() ? std::nan("") : sum / double(errors.size());
  }
  return mean;
}

}  // namespace

StudySummary summarize(const StudyRun& run) {
  StudySummary s;
  s.frames = long(run.frame_seconds.size());
  const Percentiles p = percentiles_of(run.frame_seconds);
  s.ms_p50 = 1e3 * p.p50;
  s.ms_p99 = 1e3 * p.p99;
  s.frame_budget_p99_pct = 100.0 * p.p99 / kFrameBudget_s;
  s.mean = mean_over_frames(run.errors);
  s.psnr_db = psnr_db(s.mean.frame_mse);
  s.knob_mean = mean_over_frames(run.knob_errors);
  s.knob_psnr_db = psnr_db(s.knob_mean.frame_mse);
  return s;
}

void write_study_csv(const std::string& path, const std::string& scene_name, const std::vector<StudyRun>& runs) {
  const std::string partial = path + ".partial";
  {
    std::ofstream out(partial);
    if (!out) throw std::runtime_error("cannot write '" + partial + "'");
    out << "scene,knob,value,role,backend,status,frames,ms_per_frame_p50,ms_per_frame_p99,frame_budget_p99_pct,"
           "film_l1_mm,film_l2_mm,frame_psnr_db,covered_area_rel_error,volume_rel_error,pile_height_error_mm,stain_l1,"
           "knob_film_l1_mm,knob_frame_psnr_db,knob_stain_l1\n";
    for (const StudyRun& run : runs) {
      const StudySetting& st = run.setting;
      out << field(scene_name) << ',' << st.knob << ',' << cell(st.value) << ',' << st.role << ','
          << to_string(run.backend) << ',' << field(run.status);
      if (run.status == "ok") {
        const StudySummary s = summarize(run);
        out << ',' << s.frames << ',' << cell(s.ms_p50) << ',' << cell(s.ms_p99) << ',' << cell(s.frame_budget_p99_pct)
            << ',' << cell(s.mean.film_l1_mm) << ',' << cell(s.mean.film_l2_mm) << ',' << cell(s.psnr_db) << ','
            << cell(s.mean.covered_area_rel_error) << ',' << cell(s.mean.volume_rel_error) << ','
            << cell(s.mean.pile_height_error_mm) << ',' << cell(s.mean.stain_l1) << ',' << cell(s.knob_mean.film_l1_mm)
            << ',' << cell(run.knob_errors.empty() ? std::nan("") : s.knob_psnr_db) << ',' << cell(s.knob_mean.stain_l1);
      } else {
        out << ",,,,,,,,,,,,,,";
      }
      out << '\n';
    }
    if (!out.flush()) throw std::runtime_error("cannot write '" + partial + "'");
  }
  rename_into_place(partial, path);
}

void write_study_hdf5(const std::string& path, const Study& study, const std::vector<StudyRun>& runs,
                      const std::vector<std::pair<std::string, std::string>>& attributes) {
  const std::string partial = path + ".partial";
  const H5 h5{partial};
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const hid_t file = h5.check(H5Fcreate(partial.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), "create the file");
  try {
    for (const auto& [name, value] : attributes) text_attribute(h5, file, name, value);
    text_attribute(h5, file, "reference", study.reference_description());
    text_attribute(h5, file, "grid", std::to_string(study.grid_width()) + " x " + std::to_string(study.grid_height()));
    const hid_t all = h5.check(H5Gcreate2(file, "runs", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), "create /runs");
    for (std::size_t i = 0; i < runs.size(); ++i) {
      const StudyRun& run = runs[i];
      char name[32];
      std::snprintf(name, sizeof name, "%03zu", i);
      const hid_t group = h5.check(H5Gcreate2(all, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), "create a run's group");
      text_attribute(h5, group, "knob", run.setting.knob);
      text_attribute(h5, group, "value", cell(run.setting.value));
      text_attribute(h5, group, "role", run.setting.role);
      text_attribute(h5, group, "backend", to_string(run.backend));
      text_attribute(h5, group, "status", run.status);
      number_dataset(h5, group, "frame_seconds", run.frame_seconds, "s");
      for (const ErrorColumn& column : kErrorColumns) {
        std::vector<double> values, knob_values;
        for (const FrameErrors& e : run.errors) values.push_back(e.*column.member);
        for (const FrameErrors& e : run.knob_errors) knob_values.push_back(e.*column.member);
        number_dataset(h5, group, column.name, values, column.unit);
        number_dataset(h5, group, std::string("knob_") + column.name, knob_values, column.unit);
      }
      H5Gclose(group);
    }
    H5Gclose(all);
  } catch (...) {
    H5Fclose(file);
    std::filesystem::remove(partial);
    throw;
  }
  h5.check(H5Fclose(file), "close the file");
  rename_into_place(partial, path);
}

}  // namespace bleedsim
