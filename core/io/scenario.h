#pragma once
// Scenario files (TOML, docs/scenario-format.md) → a Scene, with what the file says beside it: the
// outputs, its text and where each key was written.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/io/output_spec.h"
#include "core/io/scenario_tables.h"
#include "core/io/trace_csv.h"
#include "core/mesh/view_render.h"
#include "core/runtime/input_error.h"
#include "core/runtime/input_file.h"
#include "core/runtime/memory.h"
#include "core/runtime/params.h"
#include "core/scene/scene.h"

namespace bleedsim {

struct Scenario {
  Scene scene;
  OutputSpec output;
  std::string path;  // the scenario file
  std::string text;  // its text, recorded in every output for provenance
  std::map<std::string, SourcePlace> places;  // where each key was written, for later messages
  std::optional<ViewCamera> view;             // [view]: the tissue mesh as an endoscope sees it
  // The files it names (a trace, a mesh, a texture, a vessel map), in the order read, each with its
  // key: what a study's fingerprint hashes beside the text.
  std::vector<InputFile> files;
  // The host memory reading each of them takes at the most (a trace's samples kept, a mesh's reading,
  // a texture's decoding), under its key, in the order read: what validate says beside the backend's.
  MemoryParts input_memory;
  // How its trace was read, the run's part kept (validate reads the whole file with the same).
  TraceOptions trace_options;

  // Where `key` was written (the file alone when it was not).
  SourcePlace place_of(const std::string& key) const;
  // The same error, placed where its key was written when it came without a place (an error of
  // the simulation or the memory check, which know keys but not files).
  InputError placed(const InputError& error) const;
};

// A scenario is a description, not data: a file larger than this is refused unread.
constexpr std::uintmax_t kMaxScenarioBytes = 16u << 20;

// What reading a scenario does with its tissue, once the run is known to fit in memory: draws it
// (a run needs it), or only reads a texture's header (bleedsim validate, which allocates nothing
// the size of the panel; Scene::tissue and Scene::vessel_density stay empty).
enum class ReadTissue { draw, header_only };

// Overrides are values set from outside the file, each a TOML line "table.key=value"
// ("particles.diameter_mm=0.1"): `bleedsim hash --set`, and the Python module's dict. They are read
// as the lines of a document of this name, over what the file wrote, and checked with the file as
// if written there: a message about one reads "overrides:N:COLUMN: key: ...", N its place among them.
// Scenario::text stays the file's text.
inline constexpr const char* kOverridesName = "overrides";

// Reads, validates and resolves a scenario file: every key checked for type and range (each
// table's rules in core/), unknown keys refused, the memory the run takes counted, the tissue
// drawn or loaded. Throws InputError naming file, line, column and key.
Scenario load_scenario(const std::string& path, ReadTissue tissue = ReadTissue::draw,
                       const std::vector<std::string>& overrides = {});

// The same for text already in memory; `path` names it in messages and anchors relative paths.
Scenario parse_scenario(const std::string& text, const std::string& path, ReadTissue tissue = ReadTissue::draw,
                        const std::vector<std::string>& overrides = {});

}  // namespace bleedsim
