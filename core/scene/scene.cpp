#include "core/scene/scene.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include "core/runtime/message_text.h"

namespace bleedsim {
namespace {

// A scene's name becomes a folder under out/: no separators, spaces, or "." and "..".
bool is_folder_name(const std::string& name) {
  const auto allowed = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-';
  };
  return !name.empty() && std::isalnum(static_cast<unsigned char>(name[0])) &&
         std::all_of(name.begin(), name.end(), allowed);
}

// Without a name key the file's stem names the scene, with anything a folder name cannot hold
// replaced by '-': "my scene.toml" runs as "my-scene".
std::string name_from_file(const std::string& path) {
  std::string name = std::filesystem::path(path).stem().string();
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_') c = '-';
  if (name.empty() || !std::isalnum(static_cast<unsigned char>(name[0]))) name = "scene" + name;
  return name;
}

ParamProblem name_a_folder(Scene& scene, const Written& written, const Scene&) {
  if (!written.has("name")) scene.name = name_from_file(written.file);
  if (scene.name.size() > kMaxFileName)
    return {"name", "is " + std::to_string(scene.name.size()) + " characters long; a folder's name may be at most " +
                        std::to_string(kMaxFileName) + " (it names the output folder)"};
  if (is_folder_name(scene.name)) return {};
  return {"name", "'" + scene.name + "' must start with a letter or digit and hold only letters, digits, "
                                     "'.', '_' and '-' (it names the output folder)"};
}

ParamProblem frames_countable(const Scene& scene, const Scene&) {
  const double frames = std::round(scene.duration_s * scene.frame_rate_hz);
  if (frames >= 1 && frames <= double(kMaxFrames)) return {};
  return {"duration_s", "gives " + std::to_string(std::llround(frames)) + " frames at " + format_number(scene.frame_rate_hz) +
                            " Hz; a run needs between 1 and " + std::to_string(kMaxFrames)};
}

}  // namespace

MemoryPart Domain::memory(Count bytes_per_pixel) const {
  return {"scene.width_px", "the " + std::to_string(width_px) + " x " + std::to_string(height_px) + " px panel",
          pixels() * bytes_per_pixel};
}

PixelGrid Domain::grid() const {
  return PixelGrid{width_px, height_px, static_cast<float>(width_mm / width_px),
                   static_cast<float>(height_mm / height_px)};
}

int Scene::frame_count() const {
  return static_cast<int>(std::llround(duration_s * frame_rate_hz));
}

double Scene::frame_time_s(std::int64_t k) const {
  return static_cast<double>(k + 1) / frame_rate_hz;
}

std::int64_t Scene::haptic_ticks_through_frame(std::int64_t k) const {
  // (k + 1) · rate is exact; one division, correctly rounded, and floor: the same on every host.
  return static_cast<std::int64_t>(std::floor(static_cast<double>((k + 1) * kHapticRate_hz) / frame_rate_hz)) + 1;
}

const ParamTable<Scene>& scene_table() {
  using T = ParamType;
  using P = Scene;
  static const ParamTable<P> table{
      "scene",
      "the panel in pixels and millimetres, the duration, the frame rate and the seed (required)",
      {{"name", T::text, BLEEDSIM_MEMBER(P, name), "", {},
        "names the output folder: a letter or digit, then letters, digits, '.', '_' and '-'",
        "the file's name without .toml, other characters replaced by '-'"},
       {"width_px", T::integer, BLEEDSIM_MEMBER(P, domain.width_px), "px", {1, 65535}, "the panel's width in pixels",
        nullptr, true},
       {"height_px", T::integer, BLEEDSIM_MEMBER(P, domain.height_px), "px", {1, 65535},
        "the panel's height in pixels", nullptr, true},
       {"width_mm", T::number, BLEEDSIM_MEMBER(P, domain.width_mm), "mm", {0, 1e4, true},
        "the panel's width on the tissue", nullptr, true},
       {"height_mm", T::number, BLEEDSIM_MEMBER(P, domain.height_mm), "mm", {0, 1e4, true},
        "the panel's height on the tissue", nullptr, true},
       {"duration_s", T::number, BLEEDSIM_MEMBER(P, duration_s), "s", {0, 86400, true}, "how long the run lasts",
        nullptr, true},
       {"frame_rate_hz", T::number, BLEEDSIM_MEMBER(P, frame_rate_hz), "Hz", {0, 1000, true},
        "frames per second; frame k shows t = (k + 1) / frame_rate_hz"},
       {"seed", T::integer, BLEEDSIM_MEMBER(P, seed), "", {0, 9223372036854775807.0},
        "the procedural tissue's pattern and the particles' jitter"}},
      {{"round(duration_s × frame_rate_hz) gives between 1 and 10,000,000 frames", frames_countable}},
      name_a_folder};
  return table;
}

}  // namespace bleedsim
