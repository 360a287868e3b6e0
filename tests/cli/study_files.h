#pragma once
// A study's files read back as two runs of one study must agree on: everything but the timings,
// which differ from run to run (docs/accuracy.md).
#include <hdf5.h>

#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "tests/io/hdf5_read_back.h"

namespace bleedsim::test {

inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

inline std::vector<std::string> fields_of(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  bool quoted = false;
  for (const char c : line) {
    if (c == '"') quoted = !quoted;
    else if (c == ',' && !quoted) fields.push_back(field), field.clear();
    else field += c;
  }
  fields.push_back(field);
  return fields;
}

// A study's table without its timing columns: study.csv's time_*, jobs.csv's seconds.
inline std::string without_timings(const std::string& csv) {
  const std::vector<std::string> lines = lines_of(csv);
  const std::vector<std::string> header = fields_of(lines.at(0));
  std::string out;
  for (const std::string& line : lines) {
    const std::vector<std::string> fields = fields_of(line);
    for (std::size_t i = 0; i < fields.size(); ++i)
      if (header.at(i).rfind("time_", 0) != 0 && header.at(i) != "seconds") out += fields[i] + ',';
    out += '\n';
  }
  return out;
}

inline herr_t collect_object(hid_t, const char* name, const H5O_info_t*, void* names) {
  static_cast<std::vector<std::string>*>(names)->push_back(name);
  return 0;
}
inline herr_t collect_attribute(hid_t, const char* name, const H5A_info_t*, void* names) {
  static_cast<std::vector<std::string>*>(names)->push_back(name);
  return 0;
}

// Every attribute and dataset of a study.h5 but those under /timing, by name ("." the root,
// "settings/000@role", "ladders/blur_radius/values@unit"). Read through the HDF5 library, not
// h5dump, which the GPU machine does not have. A study's attributes are text and its datasets
// numbers (each value's bits, as %a).
inline std::map<std::string, std::string> study_data(const std::filesystem::path& path) {
  const File file(path);
  std::vector<std::string> objects;
  checked_status(H5Ovisit2(file, H5_INDEX_NAME, H5_ITER_INC, collect_object, &objects, H5O_INFO_BASIC), "visit");
  std::map<std::string, std::string> data;
  for (const std::string& name : objects) {
    if (name == "timing" || name.rfind("timing/", 0) == 0) continue;
    const Owned<H5Oclose> object(checked(H5Oopen(file, name.c_str(), H5P_DEFAULT), "open " + name));
    std::vector<std::string> attributes;
    checked_status(H5Aiterate2(object, H5_INDEX_NAME, H5_ITER_INC, nullptr, collect_attribute, &attributes),
                   "the attributes of " + name);
    for (const std::string& attribute : attributes)
      data[name + "@" + attribute] = text_attribute(object, attribute.c_str()).value;
    if (H5Iget_type(object) != H5I_DATASET) continue;
    std::string values;
    for (const double v : read_all<double>(object, H5T_NATIVE_DOUBLE)) {
      char bits[32];
      std::snprintf(bits, sizeof bits, "%a ", v);
      values += bits;
    }
    data[name] = values;
  }
  return data;
}

}  // namespace bleedsim::test
