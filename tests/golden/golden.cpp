#include "tests/golden/golden.h"

#include <hdf5.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/runtime/hash.h"
#include "core/io/hdf5_writer.h"
#include "tests/test_paths.h"

namespace bleedsim::golden {
namespace {

namespace fs = std::filesystem;

std::runtime_error bad_file(const std::string& path, const std::string& why) {
  return std::runtime_error(path + ": " + why);
}

// Closes an HDF5 handle with the function that matches its kind.
struct Handle {
  hid_t id;
  herr_t (*close)(hid_t);
  ~Handle() {
    if (id >= 0) close(id);
  }
};

std::string read_string_attribute(hid_t object, const char* name, const std::string& path) {
  Handle attr{H5Aopen(object, name, H5P_DEFAULT), H5Aclose};
  Handle type{H5Aget_type(attr.id), H5Tclose};
  if (attr.id < 0 || type.id < 0 || !H5Tis_variable_str(type.id))
    throw bad_file(path, std::string("no string attribute ") + name);
  char* text = nullptr;
  Handle memtype{H5Tcopy(H5T_C_S1), H5Tclose};
  H5Tset_size(memtype.id, H5T_VARIABLE);
  H5Tset_cset(memtype.id, H5T_CSET_UTF8);
  if (H5Aread(attr.id, memtype.id, &text) < 0) throw bad_file(path, std::string("cannot read ") + name);
  std::string value = text ? text : "";
  H5free_memory(text);
  return value;
}

// All of a dataset's bytes, in its stored element type.
std::vector<std::uint8_t> read_dataset_bytes(hid_t file, const std::string& name, const std::string& path) {
  Handle set{H5Dopen2(file, name.c_str(), H5P_DEFAULT), H5Dclose};
  if (set.id < 0) throw bad_file(path, "no dataset " + name);
  Handle type{H5Dget_type(set.id), H5Tclose};
  Handle native{H5Tget_native_type(type.id, H5T_DIR_ASCEND), H5Tclose};
  Handle space{H5Dget_space(set.id), H5Sclose};
  std::vector<std::uint8_t> bytes(std::size_t(H5Sget_simple_extent_npoints(space.id)) *
                                  H5Tget_size(native.id));
  if (H5Dread(set.id, native.id, H5S_ALL, H5S_ALL, H5P_DEFAULT, bytes.data()) < 0)
    throw bad_file(path, "cannot read dataset " + name);
  return bytes;
}

}  // namespace

std::vector<std::string> scenes() {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(test::source_dir() + "/golden"))
    if (entry.is_directory()) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::string scenario_path(const std::string& scene) {
  return test::source_dir() + "/scenarios/golden/" + scene + ".toml";
}

std::string golden_dir(const std::string& scene) { return test::source_dir() + "/golden/" + scene; }

std::vector<FieldHashes> read_hashes(const std::string& dir) {
  const std::string path = dir + "/hashes.txt";
  std::ifstream in(path);
  if (!in) throw bad_file(path, "cannot open");
  std::vector<FieldHashes> frames;
  std::string line;
  for (int line_number = 1; std::getline(in, line); ++line_number) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream words(line);
    long frame = -1;
    words >> frame;
    if (frame != long(frames.size()))
      throw bad_file(path, "line " + std::to_string(line_number) + ": expected frame " +
                               std::to_string(frames.size()));
    FieldHashes hashes;
    for (std::string word; words >> word;) {
      const std::size_t eq = word.find('=');
      if (eq == std::string::npos) throw bad_file(path, "line " + std::to_string(line_number) + ": bad entry " + word);
      hashes.emplace_back(word.substr(0, eq), std::stoull(word.substr(eq + 1), nullptr, 16));
    }
    frames.push_back(std::move(hashes));
  }
  return frames;
}

void write_hashes(const std::string& dir, const std::string& scenario,
                  const std::vector<FieldHashes>& frames) {
  std::ofstream out(dir + "/hashes.txt");
  out << "# bleedsim golden frames of " << scenario << "\n"
      << "# Written by scripts/update-goldens on the CPU reference. One line per frame:\n"
      << "# <frame> <field>=<FNV-1a 64 of the field's bytes> ...\n";
  for (std::size_t k = 0; k < frames.size(); ++k) {
    out << k;
    for (const auto& [name, hash] : frames[k]) out << ' ' << name << '=' << hex64(hash);
    out << '\n';
  }
  if (!out) throw bad_file(dir + "/hashes.txt", "cannot write");
}

std::vector<long> key_frame_numbers(long frame_count) {
  std::vector<long> frames = {0, frame_count / 3, 2 * frame_count / 3, frame_count - 1};
  frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
  return frames;
}

std::map<long, FieldBytes> read_key_frames(const std::string& dir) {
  const std::string path = dir + "/keyframes.h5";
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  Handle file{H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
  if (file.id < 0) throw bad_file(path, "cannot open");
  std::istringstream numbers(read_string_attribute(file.id, "key_frames", path));
  std::vector<long> frames;
  for (long k; numbers >> k;) frames.push_back(k);
  std::istringstream names(read_string_attribute(file.id, "fields", path));
  std::map<long, FieldBytes> key_frames;
  for (std::string name; names >> name;) {
    const std::vector<std::uint8_t> all = read_dataset_bytes(file.id, name, path);
    const std::size_t per_frame = all.size() / frames.size();
    for (std::size_t i = 0; i < frames.size(); ++i)
      key_frames[frames[i]][name].assign(all.begin() + i * per_frame, all.begin() + (i + 1) * per_frame);
  }
  return key_frames;
}

void write_key_frames(const std::string& dir, const Simulation& simulation,
                      const std::map<long, FieldBytes>& frames, const std::vector<HapticTick>& ticks) {
  std::vector<FieldLayout> specs;
  std::string names, numbers;
  for (const std::string& name : simulation.field_names()) {
    specs.push_back(*simulation.field(name).field);
    names += (names.empty() ? "" : " ") + name;
  }
  for (const auto& entry : frames) numbers += (numbers.empty() ? "" : " ") + std::to_string(entry.first);
  Hdf5FrameWriter writer(dir + "/keyframes.h5", specs,
                         {{"key_frames", numbers}, {"fields", names}}, 9, !ticks.empty());
  for (const auto& [frame, fields] : frames) {
    std::vector<const void*> data;
    for (const FieldLayout& spec : specs) data.push_back(fields.at(spec.name).data());
    // Every tick of the run goes in with the last key frame: the channel is not per key frame.
    const bool last = frame == frames.rbegin()->first;
    writer.append(simulation.scene().frame_time_s(frame), data, last ? ticks : std::vector<HapticTick>{});
  }
  writer.finish(true);
}

}  // namespace bleedsim::golden
