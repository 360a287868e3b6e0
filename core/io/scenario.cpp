#include "core/io/scenario.h"

#include "core/io/toml.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <type_traits>
#include <utility>

#include "core/effects/cuts.h"
#include "core/effects/effect_list.h"
#include "core/effects/particles/particle_params.h"
#include "core/effects/pipeline.h"
#include "core/effects/stage_kinds.h"
#include "core/effects/surface/surface_stage.h"
#include "core/effects/tips.h"
#include "core/haptics/haptic_params.h"
#include "core/io/mesh_obj.h"
#include "core/io/text_file.h"
#include "core/io/tissue_png.h"
#include "core/io/trace_csv.h"
#include "core/mesh/surface_bake.h"
#include "core/runtime/input_file.h"
#include "core/runtime/memory.h"
#include "core/runtime/message_text.h"
#include "core/runtime/tissue.h"

namespace bleedsim {
namespace {

namespace fs = std::filesystem;

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

// Reads a scenario's tables through their parameter tables (core/runtime/params.h): each value
// checked for type as it is read, then each table resolved and checked as a whole, the problem
// placed where its key was written (or at its table's header when the key was left out).
class Reader {
 public:
  explicit Reader(Scenario& scenario) : s_(scenario) {}

  // An override's region names the overrides, not the file.
  SourcePlace place(const toml::source_region& region) const {
    return {region.path ? *region.path : s_.path, int(region.begin.line), int(region.begin.column)};
  }
  [[noreturn]] void fail(const toml::source_region& where, const std::string& key, const std::string& message) const {
    throw InputError(place(where), key, message);
  }
  // A problem at its key's place, else its table's.
  [[noreturn]] void fail(const ParamProblem& problem, const std::string& table_key) const {
    const bool written = s_.places.count(problem.key) != 0;
    throw InputError(s_.place_of(written ? problem.key : table_key), problem.key, problem.message);
  }

  // A sub-table, or null when it is absent.
  const toml::table* table(const toml::table& parent, const std::string& name) {
    const toml::node* node = parent.get(name);
    if (!node) return nullptr;
    if (!node->is_table()) fail(node->source(), name, std::string("expected a table, got ") + kind_of(*node));
    s_.places[name] = place(node->source());
    return node->as_table();
  }

  // Refuses every key of the file that no table reads, all of them at once in file order (an old
  // file meets its every former key in one try). The first is the error's place and key; the rest
  // follow it a line each.
  void refuse_unknown_keys(const toml::table& root) const {
    std::vector<Unknown> unknown = unknown_keys(root);
    if (unknown.empty()) return;
    std::sort(unknown.begin(), unknown.end(), [](const Unknown& a, const Unknown& b) {
      return std::make_pair(a.where.line, a.where.column) < std::make_pair(b.where.line, b.where.column);
    });
    std::string message = unknown.front().message;
    if (unknown.size() > 1) message += " (and " + std::to_string(unknown.size() - 1) + " more below)";
    for (auto u = unknown.begin() + 1; u != unknown.end(); ++u)
      message += "\n  " + std::string(InputError(u->where, u->key, u->message).what());
    throw InputError(unknown.front().where, unknown.front().key, message);
  }

  // Reads `table`'s keys from `t` (null: the file left the whole table out) into `params`, under
  // `at` ("particles", "cut[2]"), and checks them against the table's ranges and rules; what the
  // file wrote of keys no member holds comes back.
  template <class P>
  Written read(const toml::table* t, const ParamTable<P>& table, P& params, const Scene& scene, const std::string& at) {
    const Written written = read_keys(t, table, params, scene, at);
    check(table, params, scene, at);
    return written;
  }

  // read() without the rules: an effect's rules may be about tables read after it (check()).
  template <class P>
  Written read_keys(const toml::table* t, const ParamTable<P>& table, P& params, const Scene& scene,
                    const std::string& at) {
    Written written{s_.path, {}, {}, {}};
    for (const Param<P>& param : table.params) {
      const std::string key = at + "." + param.key;
      const toml::node* node = t ? t->get(param.key) : nullptr;
      if (!node) {
        if (param.required) throw InputError(s_.place_of(at), key, "missing (required)");
        continue;
      }
      s_.places[key] = place(node->source());
      written.keys.insert(param.key);
      std::visit([&](auto field) { assign(*node, key, param, field, params, written); }, param.field);
    }
    if (table.resolve)
      if (const ParamProblem problem = table.resolve(params, written, scene))
        fail({at + "." + problem.key, problem.message}, at);
    return written;
  }

  // `params` against `table`'s ranges and rules, a problem placed at its key.
  template <class P>
  void check(const ParamTable<P>& table, const P& params, const Scene& scene, const std::string& at) const {
    if (const ParamProblem problem = check_params(table, params, scene, at)) fail(problem, at);
  }

 private:
  template <class P, class Field>
  void assign(const toml::node& node, const std::string& key, const Param<P>& param, Field field, P& params,
              Written& written) {
    if constexpr (std::is_same_v<Field, std::monostate>) {
      if (param.type == ParamType::text) written.texts[param.key] = text(node, key);
      else written.numbers[param.key] = in_range(number(node, key), node, key, param);
    } else if constexpr (std::is_same_v<Field, VectorRef (*)(P&)>) {
      const std::array<double, 3> v = vector(node, key, param);
      const VectorRef to = field(params);
      to.x = v[0];
      to.y = v[1];
      if (to.z) *to.z = v[2];
    } else if constexpr (std::is_same_v<Field, double& (*)(P&)>) {
      field(params) = in_range(number(node, key), node, key, param);
    } else if constexpr (std::is_same_v<Field, std::string& (*)(P&)>) {
      field(params) = text(node, key);
    } else if constexpr (std::is_same_v<Field, bool& (*)(P&)>) {
      const auto value = node.value_exact<bool>();
      if (!value) fail(node.source(), key, std::string("expected true or false, got ") + kind_of(node));
      field(params) = *value;
    } else if constexpr (std::is_same_v<Field, std::vector<std::string>& (*)(P&)>) {
      field(params) = names(node, key);
    } else {  // an integer member: checked against its range before it is narrowed
      const auto value = node.value_exact<std::int64_t>();
      if (!value) fail(node.source(), key, std::string("expected an integer, got ") + kind_of(node));
      in_range(double(*value), node, key, param);
      using T = std::remove_reference_t<decltype(field(params))>;
      field(params) = static_cast<T>(*value);
    }
  }

  template <class P>
  double in_range(double value, const toml::node& node, const std::string& key, const Param<P>& param) const {
    if (const ParamProblem problem = range_problem(key, param.type, param.range, value))
      fail(node.source(), key, problem.message);
    return value;
  }

  double number(const toml::node& node, const std::string& key) const {
    if (const auto i = node.value_exact<std::int64_t>()) return double(*i);
    if (const auto f = node.value_exact<double>()) return *f;
    fail(node.source(), key, std::string("expected a number, got ") + kind_of(node));
  }

  std::string text(const toml::node& node, const std::string& key) const {
    const auto value = node.value_exact<std::string>();
    if (!value) fail(node.source(), key, std::string("expected a string, got ") + kind_of(node));
    return *value;
  }

  // [x, y] or [x, y, z]: two or three numbers, each within the parameter's range (a pair's third is 0).
  template <class P>
  std::array<double, 3> vector(const toml::node& node, const std::string& key, const Param<P>& param) {
    const bool three = param.type == ParamType::vector3;
    const std::size_t size = three ? 3 : 2;
    const toml::array* array = node.as_array();
    if (!array || array->size() != size) {
      const std::string got = !array           ? kind_of(node)
                              : array->empty() ? "an empty array"
                              : "an array of " + std::to_string(array->size()) +
                                    (array->size() == 1 ? " element" : " elements");
      fail(node.source(), key, three ? "expected [x, y, z], three numbers, got " + got
                                     : "expected [x, y], two numbers, got " + got);
    }
    // In order, so an array with several bad numbers is refused at the first.
    std::array<double, 3> v{};
    const char* axes[] = {"x", "y", "z"};
    for (std::size_t i = 0; i < size; ++i) {
      const toml::node& c = *array->get(i);
      const std::string at = key + "." + axes[i];
      s_.places[at] = place(c.source());
      v[i] = in_range(number(c, at), c, at, param);
    }
    return v;
  }

  std::vector<std::string> names(const toml::node& node, const std::string& key) {
    if (!node.is_array()) fail(node.source(), key, std::string("expected an array of field names, got ") + kind_of(node));
    std::vector<std::string> values;
    const toml::array& array = *node.as_array();
    for (std::size_t i = 0; i < array.size(); ++i) {
      const std::string element = key + "[" + std::to_string(i) + "]";
      s_.places[element] = place(array[i].source());
      const auto name = array[i].value_exact<std::string>();
      if (!name) fail(array[i].source(), element, std::string("expected a field name, got ") + kind_of(array[i]));
      values.push_back(*name);
    }
    return values;
  }

  // A key no table reads: where it was written, its path ("cut[2].rate_per_s") and what is wrong.
  struct Unknown {
    SourcePlace where;
    std::string key;
    std::string message;
  };

  // The file's unknown tables, and the unknown keys of its known tables and of each [[cut]] and
  // [[tip]]; an unknown table's own keys are not looked at.
  std::vector<Unknown> unknown_keys(const toml::table& root) const {
    const std::vector<TableView> tables = scenario_tables();
    std::vector<std::string> names;
    for (const TableView& table : tables) names.push_back(table.name);
    std::vector<Unknown> unknown;
    for (const auto& [key, node] : root) {
      const std::string name(key.str());
      const auto table = std::find_if(tables.begin(), tables.end(), [&](const TableView& t) { return t.name == name; });
      if (table == tables.end()) {
        unknown.push_back({place(key.source()), name, unknown_message(name, "", "", names, "unknown table")});
        continue;
      }
      std::vector<std::string> known;
      for (const ParamView& param : table->params) known.push_back(param.key);
      if (const toml::table* t = node.as_table()) add_unknown_keys(*t, name, name, known, unknown);
      if (node.is_array_of_tables())
        for (std::size_t i = 0; i < node.as_array()->size(); ++i)
          add_unknown_keys(*(*node.as_array())[i].as_table(), name, name + "[" + std::to_string(i) + "]", known,
                           unknown);
    }
    return unknown;
  }

  // The keys of `t`, [`table`] written at `at`, that are not in `known`.
  void add_unknown_keys(const toml::table& t, const std::string& table, const std::string& at,
                        const std::vector<std::string>& known, std::vector<Unknown>& unknown) const {
    for (const auto& [key, node] : t) {
      const std::string name(key.str());
      if (std::find(known.begin(), known.end(), name) == known.end())
        unknown.push_back({place(key.source()), at + "." + name,
                           unknown_message(name, table, at, known, node.is_table() ? "unknown table" : "unknown key")});
    }
  }

  // `what` ("unknown key") said of `name` in [`table`], written at `at` ("cut[2]"; both "" for the
  // file's top level): what became of it when it is a former key, else the nearest known name, or
  // all of them.
  static std::string unknown_message(const std::string& name, const std::string& table, const std::string& at,
                                     const std::vector<std::string>& known, std::string what) {
    if (const FormerKey* former = find_former_key(table, name))
      return what + (*former->replacement ? ": replaced by " + at + "." + former->replacement : ": removed") + " (" +
             former->since + "): " + former->what;
    const std::string* nearest = nullptr;
    std::size_t best = 3;
    for (const std::string& k : known)
      if (const std::size_t d = edit_distance(name, k); d < best) best = d, nearest = &k;
    if (nearest) return what + "; did you mean '" + *nearest + "'?";
    what += " (known here:";
    for (const std::string& k : known) what += " " + k;
    return what + ")";
  }

  Scenario& s_;
};

// Refused at its header, before its keys are read: a table whose stage reads a field that no stage
// of this scene writes (a [blur] or a [trail] without [particles]).
void refuse_unwired_stages(Reader& r, const toml::table& root, Scenario& s) {
  Scene declared = s.scene;
  for_each_effect([&](const auto& effect) {
    using P = typename std::decay_t<decltype(effect)>::Params;
    if (root.contains(effect.table().name)) declared.effects.set(P{});
  });
  if (const ParamProblem problem = Pipeline::wiring_problem(declared)) {
    r.table(root, problem.key);
    throw InputError(s.place_of(problem.key), problem.key, problem.message);
  }
}

// Every effect's table: read into the scene when the file declares it (even empty), absent
// otherwise. Its rules are checked once every table they may name has been read (check_effects).
void read_effects(Reader& r, const toml::table& root, Scene& scene) {
  for_each_effect([&](const auto& effect) {
    const auto& table = effect.table();
    const toml::table* t = r.table(root, table.name);
    if (!t) return;
    typename std::decay_t<decltype(effect)>::Params params;
    r.read_keys(t, table, params, scene, table.name);
    scene.effects.set(params);
  });
}

void check_effects(const Reader& r, const Scene& scene) {
  for_each_declared_effect(scene, [&](const auto& effect, const auto& params) {
    r.check(effect.table(), params, scene, effect.table().name);
  });
}

// The [[cut]] or [[tip]] tables, in the order written; each is named "cut[i]" in messages.
template <class P>
void read_each(Reader& r, const toml::table& root, const ParamTable<P>& table, std::vector<P>& into, Scenario& s) {
  const std::string name = table.name;
  const toml::node* node = root.get(name);
  if (!node) return;
  // toml++ does not count an empty array as one of tables: "cut = []" is simply none.
  if (node->is_array() && node->as_array()->empty()) return;
  if (!node->is_array_of_tables())
    r.fail(node->source(), name, "expected [[" + name + "]] tables, got " + kind_of(*node));
  s.places[name] = r.place(node->source());
  const toml::array& array = *node->as_array();
  for (std::size_t i = 0; i < array.size(); ++i) {
    const toml::table& t = *array[i].as_table();
    const std::string key = name + "[" + std::to_string(i) + "]";
    s.places[key] = r.place(t.source());
    P point;
    r.read(&t, table, point, s.scene, key);
    into.push_back(point);
  }
}

// A file named in the scenario, relative to the scenario file.
std::string beside(const Scenario& s, const std::string& name) {
  fs::path file = name;
  if (file.is_relative()) file = fs::path(s.path).parent_path() / file;
  return file.lexically_normal().string();
}

// The file `key` names, found beside the scenario, checked (unopened) to be a regular file, and kept
// in Scenario::files.
InputFile named_file(Scenario& s, const std::string& key, const std::string& what, const std::string& name) {
  InputFile file{name.empty() ? name : beside(s, name), what, key, s.place_of(key)};
  require_regular_file(file);
  s.files.push_back(file);
  return file;
}

// The trace the [haptics] table names: the samples the run plays, up to the first past its last
// haptic tick; the lines after it are not read (validate checks them: cli/validate_command.cpp).
void load_named_trace(const Written& written, Scenario& s) {
  const InputFile file = named_file(s, "haptics.trace", "trace file", written.texts.at("trace"));
  TraceOptions& options = s.trace_options;
  const auto gap = written.numbers.find("repair_gap_ms");
  options.max_repair_gap_s = gap == written.numbers.end() ? 0.0 : gap->second / 1000.0;
  const Scene& scene = s.scene;
  options.keep_s = double(scene.haptic_ticks_through_frame(scene.frame_count() - 1) - 1) / kHapticRate_hz;
  s.scene.trace = load_trace(file, options);
  s.input_memory.push_back(trace_memory(*s.scene.trace, file));
}

void read_haptics(Reader& r, const toml::table& root, Scenario& s) {
  const toml::table* t = r.table(root, "haptics");
  if (!t) return;
  HapticParams h;
  const Written written = r.read(t, haptic_table(), h, s.scene, "haptics");
  s.scene.haptics = h;
  load_named_trace(written, s);
}

// A tissue mesh places the tissue in the device frame itself, so the flat panel's placement under
// the stylus is not the scene's to give; the hooks in the particle step (the instrument's suction
// and contact) do not yet act on a mesh; and a film with depth is derived for the flat panel (its
// walls the panel's edges, its pressure from gravity's normal part, which the mesh's maps do not keep).
void refuse_what_a_mesh_replaces(const Scenario& s) {
  const ParticleParams* particles = s.scene.effects.find<ParticleParams>();
  if (particles && particles->film_depth)
    throw InputError(s.place_of("particles.film_depth"), "particles.film_depth",
                     "a film with depth runs on the flat panel only, not on a tissue.mesh; set it to false");
  for (const char* key : {"haptics.surface_z_mm", "haptics.panel_origin_mm", "haptics.scale"})
    if (s.places.count(key))
      throw InputError(s.place_of(key), key,
                       "places the flat panel under the stylus; with tissue.mesh the mesh's placement "
                       "(tissue.mesh_position_mm, mesh_rotation_deg, mesh_scale) says where the tissue is");
  for_each_effect([&](const auto& effect) {
    const std::string table = effect.table().name;
    if (!effect.hooks.empty() && s.places.count(table))
      throw InputError(s.place_of(table), table,
                       "the instrument's " + table +
                           " acts on the flat panel only; a scene with "
                           "tissue.mesh cannot have it yet");
  });
}

// The tissue comes last: it is the one large allocation, made only once the scene is known to fit:
// the tissue, a texture's decoding and every stage's memory, each part under the key that sets it.
// [view], once the tissue is known: it draws the mesh, and a scene without one has nothing to draw.
void read_view(Reader& r, const toml::table& root, Scenario& s) {
  const toml::table* t = r.table(root, "view");
  if (!t) return;
  ViewCamera camera;
  r.read(t, view_table(), camera, s.scene, "view");
  if (!s.scene.mesh)
    throw InputError(s.place_of("view"), "view", "draws the tissue mesh from an endoscope; this scene has no "
                                                 "tissue.mesh");
  s.view = camera;
}

// What a run bakes of the mesh onto the panel (core/mesh/surface_bake.h), refused as the file is read
// so that validate refuses it too: uvs that hold no texel's centre, and a texture stretched over
// the mesh past kMaxLeastStretch.
void refuse_a_mesh_the_panel_cannot_hold(const Scenario& s) {
  const TissueMesh& mesh = s.scene.mesh->mesh();
  const TexturePanel panel = texture_panel(s.scene.domain);
  const auto refuse = [&](const std::string& why) {
    throw InputError(s.place_of("tissue.mesh"), "tissue.mesh", s.scene.mesh_source + " " + why);
  };
  if (!covers_a_texel(mesh, panel))
    refuse("covers no texel of the " + std::to_string(panel.width_px) + " × " + std::to_string(panel.height_px) +
           " texture: its uvs hold no texel's centre");
  const double least = panel_stretch(mesh, panel).least;
  if (least > kMaxLeastStretch)
    refuse("stretches the texture: a panel mm is at least " + format_significant(least, 3) +
           " mm of its surface, past the " + format_number(kMaxLeastStretch) +
           " a mesh may stretch it (its uvs span too little of the texture for its size on the " +
           format_number(panel.width_mm) + " x " + format_number(panel.height_mm) + " mm panel)");
}

// The [tissue] table, and its mesh, which the output's fields and the stages' memory depend on (the
// mesh reader keeps to its own budget).
TissueFile read_tissue_table(Reader& r, const toml::table& root, Scenario& s) {
  TissueFile tissue;
  r.read(r.table(root, "tissue"), tissue_table(), tissue, s.scene, "tissue");
  if (!tissue.mesh.empty()) {
    refuse_what_a_mesh_replaces(s);
    s.scene.mesh_source = named_file(s, "tissue.mesh", "mesh file", tissue.mesh).path;
    s.input_memory.push_back(mesh_memory(s.scene.mesh_source, "tissue.mesh"));
    try {
      s.scene.mesh = std::make_shared<const MeshSurface>(placed(load_tissue_mesh(s.scene.mesh_source), tissue.placement));
    } catch (const InputError& e) {
      throw s.placed(e);  // the memory check names the key, not where it was written
    }
    refuse_a_mesh_the_panel_cannot_hold(s);
  }
  return tissue;
}

void read_tissue(const TissueFile& tissue, Scenario& s, ReadTissue how) {
  Scene& scene = s.scene;
  const Domain& d = scene.domain;
  MemoryParts parts = Pipeline::memory(scene, resolve(scene));
  parts.push_back(scene.domain.memory(4));
  const VesselParams* vessels = scene.effects.find<VesselParams>();
  const bool procedural_vessels = vessels && vessels->map == "procedural";
  if (procedural_vessels && !tissue.texture.empty())
    throw s.placed(InputError(SourcePlace{}, "vessels.map",
                     "\"procedural\" reads the procedural tissue's vessels, and this scene's tissue is a texture: "
                     "name a PNG map of its vessels"));
  scene.tissue_source = "procedural";
  std::optional<InputFile> texture, vessel_map;
  // Each PNG's decoding, from its header; each is freed before the next, but they are counted as if
  // held together.
  MemoryParts decoding;
  if (!tissue.texture.empty()) {
    texture = named_file(s, "tissue.texture", "texture", tissue.texture);
    scene.tissue_source = texture->path;
    decoding.push_back(texture_memory(read_tissue_png_header(*texture), *texture, d.width_px, d.height_px));
  }
  // The vessels' map, like the tissue's texture.
  if (vessels) {
    parts.push_back({"vessels.map", "the vessel density map", scene.domain.pixels() * Count(sizeof(float))});
    if (!procedural_vessels) {
      vessel_map = named_file(s, "vessels.map", "vessel map", vessels->map);
      decoding.push_back(texture_memory(read_tissue_png_header(*vessel_map), *vessel_map, d.width_px, d.height_px));
    }
  }
  parts.insert(parts.end(), decoding.begin(), decoding.end());
  s.input_memory.insert(s.input_memory.end(), decoding.begin(), decoding.end());
  try {
    require_memory(parts, available_host_memory(), "host");
  } catch (const InputError& e) {
    throw s.placed(e);
  }
  if (how == ReadTissue::header_only) return;
  scene.tissue = texture ? load_tissue_png(*texture, d.width_px, d.height_px)
                        : procedural_tissue(d.width_px, d.height_px, scene.seed);
  if (procedural_vessels) scene.vessel_density = procedural_vessel_density(d.width_px, d.height_px, scene.seed);
  if (vessel_map) {
    const Image density = load_tissue_png(*vessel_map, d.width_px, d.height_px);
    scene.vessel_density.resize(std::size_t(d.width_px) * std::size_t(d.height_px));
    for (std::size_t p = 0; p < scene.vessel_density.size(); ++p)
      scene.vessel_density[p] = float(density.rgba[4 * p]) / 255.0f;
  }
}

// A TOML parse error at its place in the document named `path`.
toml::table parse_toml(const std::string& text, const std::string& path) {
  try {
    return toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    const auto& begin = e.source().begin;
    throw InputError(SourcePlace{path, int(begin.line), int(begin.column)}, "", std::string(e.description()));
  }
}

// Puts each value of `overrides` into `into` at its path, over what the file wrote, keeping the
// override's place so that the reader's messages point at it. A table the file wrote another way
// (an array of [[cut]] tables) cannot be reached by a path: refused, naming the override. Values
// are moved: a copied toml++ node loses its place.
void override_values(toml::table& into, toml::table& overrides, const std::string& at) {
  for (auto&& [key, node] : overrides) {
    const std::string path = at.empty() ? std::string(key.str()) : at + "." + std::string(key.str());
    toml::node* existing = into.get(key);
    if (node.is_table() && existing && existing->is_table()) {
      override_values(*existing->as_table(), *node.as_table(), path);
    } else if (node.is_table() && existing) {
      const toml::source_region& where = key.source();
      throw InputError(SourcePlace{*where.path, int(where.begin.line), int(where.begin.column)}, path,
                       std::string("cannot be overridden by a path: the scenario holds ") + kind_of(*existing) +
                           " here");
    } else {
      into.insert_or_assign(key, std::move(node));
    }
  }
}

}  // namespace

SourcePlace Scenario::place_of(const std::string& key) const {
  const auto it = places.find(key);
  return it != places.end() ? it->second : SourcePlace{path, 0, 0};
}

InputError Scenario::placed(const InputError& error) const {
  if (!error.where().file.empty()) return error;
  const std::string prefix = error.key() + ": ";
  const std::string what = error.what();
  const std::string message = what.compare(0, prefix.size(), prefix) == 0 ? what.substr(prefix.size()) : what;
  // A key the file left out (a default set the size) is placed at its table's header.
  const std::string& key = error.key();
  const std::string table = key.substr(0, key.find_first_of(".["));
  return InputError(places.count(key) || !places.count(table) ? place_of(key) : place_of(table), key, message);
}

Scenario parse_scenario(const std::string& text, const std::string& path, ReadTissue tissue,
                        const std::vector<std::string>& overrides) {
  toml::table root = parse_toml(text, path);
  std::string override_lines;
  for (std::size_t i = 0; i < overrides.size(); ++i) {
    // One line each, so that N in "overrides:N" is the override's place among them.
    const std::size_t end = overrides[i].find_first_of("\r\n");
    if (end != std::string::npos)
      throw InputError(SourcePlace{kOverridesName, int(i + 1), int(end + 1)}, "",
                       "an override is one line, table.key=value");
    override_lines += overrides[i] + "\n";
  }
  toml::table override_table = parse_toml(override_lines, kOverridesName);
  override_values(root, override_table, "");
  Scenario s;
  s.path = path;
  s.text = text;
  Reader r(s);
  r.refuse_unknown_keys(root);
  const toml::table* scene = r.table(root, "scene");
  if (!scene) throw InputError(SourcePlace{path, 0, 0}, "scene", "missing the [scene] table (required)");
  r.read(scene, scene_table(), s.scene, s.scene, "scene");
  refuse_unwired_stages(r, root, s);
  read_effects(r, root, s.scene);
  read_haptics(r, root, s);
  read_each(r, root, tip_table(), s.scene.tips, s);
  // The effects' rules once the instrument is known (the suction needs one), then the cuts, whose
  // defaults and rules come from the effects, then the path as a whole.
  check_effects(r, s.scene);
  read_each(r, root, cut_table(), s.scene.cuts, s);
  if (const ParamProblem problem = tip_path_problem(s.scene))
    throw InputError(s.place_of(problem.key), problem.key, problem.message);
  const TissueFile tissue_file = read_tissue_table(r, root, s);
  read_view(r, root, s);
  r.read(r.table(root, "output"), output_table(), s.output, s.scene, "output");
  read_tissue(tissue_file, s, tissue);
  return s;
}

Scenario load_scenario(const std::string& path, ReadTissue tissue, const std::vector<std::string>& overrides) {
  return parse_scenario(read_text_file(path, "scenario", kMaxScenarioBytes), path, tissue, overrides);
}

}  // namespace bleedsim
