#include "core/io/scenario.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <optional>
#include <sstream>
#include <tuple>
#include <utility>

#include "core/haptics/haptics.h"
#include "core/io/trace_csv.h"
#include "core/runtime/memory.h"
#include "core/runtime/message_text.h"
#include "core/effects/particle_model.h"
#include "core/effects/pipeline.h"
#include "core/io/tissue_png.h"
#include "core/runtime/tissue.h"

namespace bleedsim {
namespace {

namespace fs = std::filesystem;

// Each effect's fields, as [output].fields may name them.
struct KnownField {
  const char* name;
  const char* effect;  // the table that must be present for the field to exist
};
const KnownField kFields[] = {{"spread/stain", "spread"},          {"splat/thickness", "particles"},
                              {"blur/thickness", "blur"},
                              {"particles/accounting", "particles"}, {"particles/position", "particles"},
                              {"particles/velocity", "particles"},   {"particles/age", "particles"}};

constexpr std::int64_t kMaxFrames = 10'000'000;


const char* kind_of(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a floating-point number";
    case toml::node_type::boolean: return "a boolean";
    case toml::node_type::table: return "a table";
    case toml::node_type::array: return "an array";
    default: return "a date or time";
  }
}

// An allowed interval for a number; `above` makes the lower end exclusive (sizes must be > 0).
struct Bounds {
  double low, high;
  bool above = false;

  bool contains(double v) const { return (above ? v > low : v >= low) && v <= high; }
  std::string describe() const {
    return above ? "greater than " + format_number(low) + " and at most " + format_number(high)
                 : "between " + format_number(low) + " and " + format_number(high);
  }
};

// Reads one scenario's tables: every value checked for type and range, every key's place
// recorded in the Scene for messages that come later (memory, output folder).
class Reader {
 public:
  Reader(Scene& scene, std::string path) : scene_(scene), path_(std::move(path)) {}

  SourcePlace place(const toml::source_region& region) const {
    return {path_, int(region.begin.line), int(region.begin.column)};
  }
  [[noreturn]] void fail(const toml::source_region& where, const std::string& key,
                         const std::string& message) const {
    throw InputError(place(where), key, message);
  }

  // A sub-table, or null when it is absent. `key` is its dotted path for messages.
  const toml::table* table(const toml::table& parent, const std::string& name, const std::string& key) {
    const toml::node* node = parent.get(name);
    if (!node) return nullptr;
    if (!node->is_table()) fail(node->source(), key, std::string("expected a table, got ") + kind_of(*node));
    scene_.places[key] = place(node->source());
    return node->as_table();
  }

  // Refuses every key of `t` not in `known`, suggesting the nearest known one.
  void only_known(const toml::table& t, const std::string& prefix, std::initializer_list<const char*> known) {
    for (const auto& [key, node] : t) {
      const std::string name(key.str());
      if (std::any_of(known.begin(), known.end(), [&](const char* k) { return name == k; })) continue;
      std::string message = node.is_table() ? "unknown table" : "unknown key";
      const char* nearest = nullptr;
      std::size_t best = 3;
      for (const char* k : known)
        if (const std::size_t d = edit_distance(name, k); d < best) best = d, nearest = k;
      if (nearest) message += "; did you mean '" + std::string(nearest) + "'?";
      else {
        message += " (known here:";
        for (const char* k : known) message += std::string(" ") + k;
        message += ")";
      }
      fail(key.source(), prefix.empty() ? name : prefix + "." + name, message);
    }
  }

  std::optional<double> number(const toml::table& t, const std::string& prefix, const char* name, Bounds bounds) {
    const toml::node* node = located(t, prefix, name);
    if (!node) return std::nullopt;
    const std::string key = prefix + "." + name;
    double value;
    if (const auto i = node->value_exact<std::int64_t>()) value = double(*i);
    else if (const auto f = node->value_exact<double>()) value = *f;
    else fail(node->source(), key, std::string("expected a number, got ") + kind_of(*node));
    if (!std::isfinite(value)) fail(node->source(), key, "must be a finite number (got " + format_number(value) + ")");
    if (!bounds.contains(value))
      fail(node->source(), key, "must be " + bounds.describe() + " (got " + format_number(value) + ")");
    return value;
  }

  std::optional<std::int64_t> integer(const toml::table& t, const std::string& prefix, const char* name,
                                      std::int64_t low, std::int64_t high) {
    const toml::node* node = located(t, prefix, name);
    if (!node) return std::nullopt;
    const std::string key = prefix + "." + name;
    const auto value = node->value_exact<std::int64_t>();
    if (!value) fail(node->source(), key, std::string("expected an integer, got ") + kind_of(*node));
    if (*value < low || *value > high)
      fail(node->source(), key,
           "must be between " + std::to_string(low) + " and " + std::to_string(high) + " (got " +
               std::to_string(*value) + ")");
    return *value;
  }

  std::optional<std::string> string(const toml::table& t, const std::string& prefix, const char* name) {
    const toml::node* node = located(t, prefix, name);
    if (!node) return std::nullopt;
    const auto value = node->value_exact<std::string>();
    if (!value) fail(node->source(), prefix + "." + name, std::string("expected a string, got ") + kind_of(*node));
    return *value;
  }

  std::optional<bool> boolean(const toml::table& t, const std::string& prefix, const char* name) {
    const toml::node* node = located(t, prefix, name);
    if (!node) return std::nullopt;
    const auto value = node->value_exact<bool>();
    if (!value) fail(node->source(), prefix + "." + name, std::string("expected true or false, got ") + kind_of(*node));
    return *value;
  }

  template <class T>
  T required(std::optional<T> value, const std::string& table_key, const char* name) const {
    if (!value) throw InputError(scene_.place_of(table_key), table_key + "." + name, "missing (required)");
    return *value;
  }

  const std::string& path() const { return path_; }
  void note_place(const std::string& key, const toml::source_region& region) { scene_.places[key] = place(region); }

 private:
  const toml::node* located(const toml::table& t, const std::string& prefix, const char* name) {
    const toml::node* node = t.get(name);
    if (node) scene_.places[prefix + "." + name] = place(node->source());
    return node;
  }

  Scene& scene_;
  std::string path_;
};

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
  std::string name = fs::path(path).stem().string();
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_') c = '-';
  if (name.empty() || !std::isalnum(static_cast<unsigned char>(name[0]))) name = "scene" + name;
  return name;
}

const Bounds kPositiveSize{0.0, 10000.0, true};
const Bounds kGrowth{0.0, 1000.0, true};
const Bounds kSeconds{0.0, 86400.0};
const Bounds kParticleRate{0.0, kMaxParticleRate};

void read_scene_table(Reader& r, const toml::table& root, Scene& scene) {
  const toml::table* t = r.table(root, "scene", "scene");
  if (!t) throw InputError(SourcePlace{r.path(), 0, 0}, "scene", "missing the [scene] table (required)");
  r.only_known(*t, "scene",
               {"name", "width_px", "height_px", "width_mm", "height_mm", "duration_s", "frame_rate_hz", "seed"});
  const std::optional<std::string> name = r.string(*t, "scene", "name");
  scene.name = name ? *name : name_from_file(r.path());
  if (!is_folder_name(scene.name))
    throw InputError(scene.place_of("scene.name"), "scene.name",
                     "'" + scene.name + "' must start with a letter or digit and hold only letters, digits, "
                     "'.', '_' and '-' (it names the output folder)");
  scene.domain.width_px = int(r.required(r.integer(*t, "scene", "width_px", 1, 65535), "scene", "width_px"));
  scene.domain.height_px = int(r.required(r.integer(*t, "scene", "height_px", 1, 65535), "scene", "height_px"));
  scene.domain.width_mm = r.required(r.number(*t, "scene", "width_mm", kPositiveSize), "scene", "width_mm");
  scene.domain.height_mm = r.required(r.number(*t, "scene", "height_mm", kPositiveSize), "scene", "height_mm");
  scene.duration_s = r.required(r.number(*t, "scene", "duration_s", {0.0, 86400.0, true}), "scene", "duration_s");
  scene.frame_rate_hz = r.number(*t, "scene", "frame_rate_hz", {0.0, 1000.0, true}).value_or(30.0);
  scene.seed = std::uint64_t(r.integer(*t, "scene", "seed", 0, INT64_MAX).value_or(0));
  const std::int64_t frames = std::llround(scene.duration_s * scene.frame_rate_hz);
  if (frames < 1 || frames > kMaxFrames)
    throw InputError(scene.place_of("scene.duration_s"), "scene.duration_s",
                     "gives " + std::to_string(frames) + " frames at " + format_number(scene.frame_rate_hz) +
                         " Hz; a run needs between 1 and " + std::to_string(kMaxFrames));
}

void read_spread_table(Reader& r, const toml::table& root, Scene& scene) {
  const toml::table* t = r.table(root, "spread", "spread");
  if (!t) return;
  r.only_known(*t, "spread", {"radius_mm", "growth_per_s"});
  SpreadParams spread;
  spread.radius_mm = r.number(*t, "spread", "radius_mm", kPositiveSize).value_or(spread.radius_mm);
  spread.growth_per_s = r.number(*t, "spread", "growth_per_s", kGrowth).value_or(spread.growth_per_s);
  scene.spread = spread;
}

// Reads a [x, y] pair of numbers, each within `bounds`.
std::optional<std::pair<double, double>> read_vector(Reader& r, const toml::table& t, const std::string& prefix,
                                                     const char* name, Bounds bounds) {
  const toml::node* node = t.get(name);
  if (!node) return std::nullopt;
  const std::string key = prefix + "." + name;
  const toml::array* pair = node->as_array();
  if (!pair || pair->size() != 2) {
    const std::string got = !pair           ? kind_of(*node)
                            : pair->empty() ? "an empty array"
                            : "an array of " + std::to_string(pair->size()) +
                                  (pair->size() == 1 ? " element" : " elements");
    r.fail(node->source(), key, "expected [x, y], two numbers, got " + got);
  }
  const auto component = [&](int i, const char* axis) {
    const toml::node& v = *pair->get(std::size_t(i));
    double value;
    if (const auto n = v.value_exact<std::int64_t>()) value = double(*n);
    else if (const auto f = v.value_exact<double>()) value = *f;
    else r.fail(v.source(), key + "." + axis, std::string("expected a number, got ") + kind_of(v));
    if (!std::isfinite(value))
      r.fail(v.source(), key + "." + axis, "must be a finite number (got " + format_number(value) + ")");
    if (!bounds.contains(value))
      r.fail(v.source(), key + "." + axis, "must be " + bounds.describe() + " (got " + format_number(value) + ")");
    return value;
  };
  r.note_place(key, node->source());
  // x before y, so a pair with two bad numbers is refused at the first (function arguments have
  // no order of evaluation).
  const double x = component(0, "x");
  const double y = component(1, "y");
  return std::make_pair(x, y);
}

void read_particles_table(Reader& r, const toml::table& root, Scene& scene) {
  const toml::table* t = r.table(root, "particles", "particles");
  if (!t) return;
  const std::string k = "particles";
  r.only_known(*t, k,
               {"capacity", "diameter_mm", "cell_mm", "max_per_cell", "rate_per_s", "volume_mm3_per_s",
                "particle_volume_mm3", "bleed_s", "lifetime_s", "fade_s", "gravity_mm_s2", "drag_per_s",
                "stiffness_per_s2", "damping_per_s", "max_speed_mm_s", "substeps", "jitter_mm", "velocity_mm_s",
                "velocity_jitter_mm_s", "splat_radius_mm"});
  ParticleParams p;
  p.capacity = int(r.integer(*t, k, "capacity", 1, 1 << 28).value_or(p.capacity));
  p.diameter_mm = r.number(*t, k, "diameter_mm", {0.0, 100.0, true}).value_or(p.diameter_mm);
  p.cell_mm = r.number(*t, k, "cell_mm", {p.diameter_mm, 10000.0}).value_or(0.0);
  p.max_per_cell = int(r.integer(*t, k, "max_per_cell", 1, 1024).value_or(p.max_per_cell));
  const std::optional<double> rate = r.number(*t, k, "rate_per_s", kParticleRate);
  const std::optional<double> volume = r.number(*t, k, "volume_mm3_per_s", {0.0, 1.0e6});
  const std::optional<double> each = r.number(*t, k, "particle_volume_mm3", {0.0, 1.0e6, true});
  if (rate && volume)
    throw InputError(scene.place_of(k + ".volume_mm3_per_s"), k + ".volume_mm3_per_s",
                     "give either rate_per_s or volume_mm3_per_s, not both");
  // A particle's volume is the blood its splat spreads; with a volume rate it also sets the count.
  if (volume && !each)
    throw InputError(scene.place_of(k + ".volume_mm3_per_s"), k + ".volume_mm3_per_s",
                     "needs particle_volume_mm3 beside it");
  p.particle_volume_mm3 = each.value_or(p.particle_volume_mm3);
  if (volume) {
    p.rate_per_s = *volume / *each;
    if (!kParticleRate.contains(p.rate_per_s))
      throw InputError(scene.place_of(k + ".volume_mm3_per_s"), k + ".volume_mm3_per_s",
                       "gives " + format_number(p.rate_per_s) + " particles per second; at most " +
                           format_number(kMaxParticleRate));
  } else {
    p.rate_per_s = rate.value_or(p.rate_per_s);
  }
  p.bleed_s = r.number(*t, k, "bleed_s", kSeconds).value_or(p.bleed_s);
  p.lifetime_s = r.number(*t, k, "lifetime_s", {0.0, 86400.0, true}).value_or(p.lifetime_s);
  p.fade_s = r.number(*t, k, "fade_s", {0.0, p.lifetime_s, true}).value_or(std::min(p.fade_s, p.lifetime_s));
  if (const auto g = read_vector(r, *t, k, "gravity_mm_s2", {-1.0e6, 1.0e6}))
    std::tie(p.gravity_x_mm_s2, p.gravity_y_mm_s2) = *g;
  p.drag_per_s = r.number(*t, k, "drag_per_s", {0.0, 1.0e6}).value_or(p.drag_per_s);
  p.stiffness_per_s2 = r.number(*t, k, "stiffness_per_s2", {0.0, 1.0e12, true}).value_or(p.stiffness_per_s2);
  p.damping_per_s = r.number(*t, k, "damping_per_s", {0.0, 1.0e6}).value_or(p.damping_per_s);
  p.max_speed_mm_s = r.number(*t, k, "max_speed_mm_s", {0.0, 1.0e5, true}).value_or(p.max_speed_mm_s);
  p.substeps = int(r.integer(*t, k, "substeps", 1, 100000).value_or(p.substeps));
  p.jitter_mm = r.number(*t, k, "jitter_mm", {0.0, 100.0}).value_or(p.jitter_mm);
  if (const auto v = read_vector(r, *t, k, "velocity_mm_s", {-1.0e5, 1.0e5}))
    std::tie(p.velocity_x_mm_s, p.velocity_y_mm_s) = *v;
  p.velocity_jitter_mm_s = r.number(*t, k, "velocity_jitter_mm_s", {0.0, 1.0e5}).value_or(p.velocity_jitter_mm_s);
  p.splat_radius_mm = r.number(*t, k, "splat_radius_mm", {0.0, 100.0, true}).value_or(0.0);
  scene.particles = p;
  const SettingsProblem problem = particle_settings_problem(scene);
  // A key the file leaves at its default is placed at the [particles] header, as a missing
  // required key is placed at its table, so the message still points at a line.
  if (!problem.key.empty())
    throw InputError(scene.place_of(scene.places.count(problem.key) ? problem.key : k), problem.key,
                     problem.message);
}

void read_blur_table(Reader& r, const toml::table& root, Scene& scene) {
  const toml::table* t = r.table(root, "blur", "blur");
  if (!t) return;
  r.only_known(*t, "blur", {"downsample", "radius_px", "sigma_px"});
  if (!scene.particles)
    throw InputError(scene.place_of("blur"), "blur", "blurs the particles' film: this scene declares no [particles]");
  BlurParams b;
  b.downsample = int(r.integer(*t, "blur", "downsample", 1, 4).value_or(b.downsample));
  if (b.downsample == 3) throw InputError(scene.place_of("blur.downsample"), "blur.downsample", "must be 1, 2 or 4 (got 3)");
  b.radius_px = int(r.integer(*t, "blur", "radius_px", 0, 64).value_or(b.radius_px));
  b.sigma_px = r.number(*t, "blur", "sigma_px", {0.0, 64.0, true}).value_or(std::max(0.5, b.radius_px / 2.0));
  scene.blur = b;
}

void read_cuts(Reader& r, const toml::table& root, Scene& scene) {
  const toml::node* node = root.get("cut");
  if (!node) return;
  // toml++ does not count an empty array as one of tables: "cut = []" is simply no cuts.
  if (node->is_array() && node->as_array()->empty()) return;
  if (!node->is_array_of_tables())
    r.fail(node->source(), "cut", std::string("expected cuts as [[cut]] tables, got ") + kind_of(*node));
  const SpreadParams defaults = scene.spread.value_or(SpreadParams{});
  const toml::array& cuts = *node->as_array();
  for (std::size_t i = 0; i < cuts.size(); ++i) {
    const toml::table& t = *cuts[i].as_table();
    const std::string key = "cut[" + std::to_string(i) + "]";
    scene.places[key] = r.place(t.source());
    r.only_known(t, key, {"x_mm", "y_mm", "start_s", "radius_mm", "growth_per_s", "rate_per_s", "bleed_s"});
    Cut cut;
    cut.x_mm = r.required(r.number(t, key, "x_mm", {0.0, scene.domain.width_mm}), key, "x_mm");
    cut.y_mm = r.required(r.number(t, key, "y_mm", {0.0, scene.domain.height_mm}), key, "y_mm");
    cut.start_s = r.number(t, key, "start_s", {0.0, 86400.0}).value_or(0.0);
    cut.radius_mm = r.number(t, key, "radius_mm", kPositiveSize).value_or(defaults.radius_mm);
    cut.growth_per_s = r.number(t, key, "growth_per_s", kGrowth).value_or(defaults.growth_per_s);
    const ParticleParams flow = scene.particles.value_or(ParticleParams{});
    cut.rate_per_s = r.number(t, key, "rate_per_s", kParticleRate).value_or(flow.rate_per_s);
    cut.bleed_s = r.number(t, key, "bleed_s", kSeconds).value_or(flow.bleed_s);
    for (const char* particle_key : {"rate_per_s", "bleed_s"})
      if (t.contains(particle_key) && !scene.particles)
        throw InputError(scene.place_of(key + "." + particle_key), key + "." + particle_key,
                         "has no effect: this scene declares no [particles]");
    scene.cuts.push_back(cut);
  }
}

void read_haptics_table(Reader& r, const toml::table& root, Scene& scene) {
  const toml::table* t = r.table(root, "haptics", "haptics");
  if (!t) return;
  const std::string k = "haptics";
  r.only_known(*t, k,
               {"trace", "repair_gap_ms", "surface_z_mm", "panel_origin_mm", "scale", "stiffness_N_per_m",
                "damping_Ns_per_m", "device_damping_Ns_per_m", "max_force_N", "cut_button", "cut_spacing_mm"});
  HapticParams h;
  h.surface_z_mm = r.number(*t, k, "surface_z_mm", {1000 * kFalconMinZ_m, 1000 * kFalconMaxZ_m}).value_or(h.surface_z_mm);
  h.origin_x_mm = scene.domain.width_mm / 2;
  h.origin_y_mm = scene.domain.height_mm / 2;
  if (const auto origin = read_vector(r, *t, k, "panel_origin_mm", {-1.0e4, 1.0e4}))
    std::tie(h.origin_x_mm, h.origin_y_mm) = *origin;
  h.scale = r.number(*t, k, "scale", {0.0, 100.0, true}).value_or(h.scale);
  h.stiffness_N_per_m = r.number(*t, k, "stiffness_N_per_m", {0.0, 3000.0, true}).value_or(h.stiffness_N_per_m);
  h.damping_Ns_per_m = r.number(*t, k, "damping_Ns_per_m", {0.0, 20.0}).value_or(h.damping_Ns_per_m);
  h.device_damping_Ns_per_m =
      r.number(*t, k, "device_damping_Ns_per_m", {0.0, 20.0, true}).value_or(h.device_damping_Ns_per_m);
  h.max_force_N = r.number(*t, k, "max_force_N", {0.0, kFalconMaxForce_N, true}).value_or(h.max_force_N);
  h.cut_buttons = std::uint8_t(r.integer(*t, k, "cut_button", 1, 15).value_or(h.cut_buttons));
  h.cut_spacing_mm = r.number(*t, k, "cut_spacing_mm", {0.05, 100.0}).value_or(h.cut_spacing_mm);
  // Checked here, where the keys have lines; a key left at its default points at [haptics].
  const PassivityProblem problem = passivity_problem(h);
  if (!problem.key.empty())
    throw InputError(scene.place_of(scene.places.count(problem.key) ? problem.key : k), problem.key, problem.message);
  scene.haptics = h;

  const std::string trace = r.required(r.string(*t, k, "trace"), k, "trace");
  const double repair_gap_ms = r.number(*t, k, "repair_gap_ms", {0.0, 1000.0}).value_or(0.0);
  fs::path file = trace;
  if (file.is_relative()) file = fs::path(r.path()).parent_path() / file;
  std::error_code ec;
  if (!fs::is_regular_file(file, ec))
    throw InputError(scene.place_of(k + ".trace"), k + ".trace",
                     "no trace file at '" + file.lexically_normal().string() + "'" +
                         (fs::is_directory(file, ec) ? " (it is a folder)" : "") + " (relative paths are to the scenario file)");
  scene.trace = load_trace(file.lexically_normal().string(), TraceOptions{repair_gap_ms / 1000.0});
}

void read_output_table(Reader& r, const toml::table& root, Scene& scene) {
  OutputSpec& out = scene.output;
  out.dir = "out/" + scene.name;
  const toml::table* t = r.table(root, "output", "output");
  if (!t) return;
  r.only_known(*t, "output", {"dir", "hdf5", "png_every", "contact_sheet", "deflate", "fields"});
  out.dir = r.string(*t, "output", "dir").value_or(out.dir);
  if (out.dir.empty()) throw InputError(scene.place_of("output.dir"), "output.dir", "must not be empty");
  out.hdf5 = r.boolean(*t, "output", "hdf5").value_or(out.hdf5);
  out.png_every = int(r.integer(*t, "output", "png_every", 0, 1000000).value_or(out.png_every));
  out.contact_sheet = int(r.integer(*t, "output", "contact_sheet", 0, 64).value_or(out.contact_sheet));
  out.deflate_level = int(r.integer(*t, "output", "deflate", 0, 9).value_or(out.deflate_level));
  const toml::node* fields = t->get("fields");
  if (!fields) return;
  scene.places["output.fields"] = r.place(fields->source());
  if (!fields->is_array()) r.fail(fields->source(), "output.fields", std::string("expected an array of field names, got ") + kind_of(*fields));
  const toml::array& names = *fields->as_array();
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string key = "output.fields[" + std::to_string(i) + "]";
    const auto name = names[i].value_exact<std::string>();
    if (!name) r.fail(names[i].source(), key, std::string("expected a field name, got ") + kind_of(names[i]));
    const auto known = std::find_if(std::begin(kFields), std::end(kFields), [&](const KnownField& f) { return *name == f.name; });
    if (known == std::end(kFields)) {
      std::string all;
      for (const KnownField& f : kFields) all += std::string(all.empty() ? "" : ", ") + f.name;
      r.fail(names[i].source(), key, "unknown field '" + *name + "' (known: " + all + ")");
    }
    if (!root.contains(known->effect))
      r.fail(names[i].source(), key, "'" + *name + "' needs the [" + known->effect + "] effect, which this scene does not declare");
    if (std::find(out.fields.begin(), out.fields.end(), *name) != out.fields.end())
      r.fail(names[i].source(), key, "'" + *name + "' is listed twice");
    out.fields.push_back(*name);
  }
}

// The tissue comes last: it is the one large allocation, made only once the scene is known to fit.
void read_tissue(Reader& r, const toml::table& root, Scene& scene) {
  const toml::table* t = r.table(root, "tissue", "tissue");
  std::optional<std::string> texture;
  if (t) {
    r.only_known(*t, "tissue", {"texture"});
    texture = r.string(*t, "tissue", "texture");
  }
  const std::size_t tissue_bytes = std::size_t(scene.domain.pixel_count()) * 4;
  require_room(scene, tissue_bytes + Pipeline::backend_bytes(scene), available_host_memory(), "host");
  if (!texture) {
    scene.tissue = procedural_tissue(scene.domain.width_px, scene.domain.height_px, scene.seed);
    scene.tissue_source = "procedural";
    return;
  }
  fs::path file = *texture;
  if (file.is_relative()) file = fs::path(r.path()).parent_path() / file;
  scene.tissue_source = file.lexically_normal().string();
  scene.tissue = load_tissue_png(scene.tissue_source, scene.domain.width_px, scene.domain.height_px,
                                 scene.place_of("tissue.texture"), "tissue.texture");
}

}  // namespace

Scene parse_scenario(const std::string& text, const std::string& path) {
  toml::table root;
  try {
    root = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    const auto& begin = e.source().begin;
    throw InputError(SourcePlace{path, int(begin.line), int(begin.column)}, "", std::string(e.description()));
  }
  Scene scene;
  scene.source_path = path;
  scene.source_text = text;
  Reader reader(scene, path);
  reader.only_known(root, "", {"scene", "tissue", "spread", "particles", "blur", "haptics", "cut", "output"});
  read_scene_table(reader, root, scene);
  read_spread_table(reader, root, scene);
  read_particles_table(reader, root, scene);
  read_blur_table(reader, root, scene);
  read_cuts(reader, root, scene);
  read_haptics_table(reader, root, scene);
  read_output_table(reader, root, scene);
  read_tissue(reader, root, scene);
  return scene;
}

Scene load_scenario(const std::string& path) {
  const SourcePlace file{path, 0, 0};
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw InputError(file, "", "cannot read scenario file: it is a folder");
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(file, "", std::string("cannot read scenario file: ") + std::strerror(errno ? errno : ENOENT));
  std::ostringstream text;
  text << in.rdbuf();
  return parse_scenario(text.str(), path);
}

}  // namespace bleedsim
