#pragma once
// Every stage bleedsim knows, as data: what calls for it, the fields it writes and reads, what it
// costs and how to build it. The pipeline (core/effects/pipeline.h) runs the stages a scene wants in
// an order derived from their reads and writes; other code asks here which stage writes a field and
// which scenario table calls for it. Adding an effect adds one row (core/effects/stage_kinds.cpp).
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "core/runtime/backend.h"
#include "core/scene/scene.h"
#include "core/scene/state.h"

namespace bleedsim {

class Stage;

struct StageKind {
  const char* name;   // its launches are counted under it
  const char* table;  // the scenario table that calls for it ("particles" for the splat); "" for every scene
  bool (*wanted)(const Scene&);
  // What it adds to State, in that order: everything but the sizes (an image covers the scene's
  // panel; the stage sizes any other field).
  std::vector<FieldLayout> writes;
  // What it reads, in this scene: fields that stages before it write.
  std::vector<std::string> (*reads)(const Scene&);
  MemoryParts (*memory_for)(const Scene&);  // the backend memory it will allocate
  std::unique_ptr<Stage> (*make)(const StageKind&, const Scene&, State&, Backend&);

  // Its declaration of `field`, or null when it does not write it.
  const FieldLayout* written(const std::string& field) const;
};

// Every stage kind, ties in the run order broken by this order.
const std::vector<StageKind>& stage_kinds();
// The kind that writes `field`, or null when none does.
const StageKind* stage_writing(const std::string& field);

}  // namespace bleedsim
