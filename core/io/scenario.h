#pragma once
// Scenario files (TOML, docs/scenario-format.md) → Scene.
#include <string>

#include "core/runtime/scene.h"

namespace bleedsim {

// Reads, validates and resolves a scenario file: every key checked for type and range, unknown
// keys refused, the tissue texture loaded. Throws InputError naming file, line, column and key.
Scene load_scenario(const std::string& path);

// The same for text already in memory; `path` names it in messages and anchors relative paths.
Scene parse_scenario(const std::string& text, const std::string& path);

}  // namespace bleedsim
