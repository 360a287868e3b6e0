#pragma once
// Every stage bleedsim knows, as data: what calls for it, the fields it writes and reads, what it
// costs and how to build it. The pipeline (core/effects/pipeline.h) runs the stages a scene wants in
// an order derived from their reads and writes; other code asks here which stage writes a field and
// which scenario table calls for it. An effect of the stage kind lists its stages in its row
// (core/effects/effect.h); stage_kinds() gathers them from the list of effects.
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "core/effects/resolved.h"
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
  MemoryParts (*memory_for)(const Scene&, const Resolved&);  // the backend memory it will allocate
  std::unique_ptr<Stage> (*make)(const StageKind&, const Scene&, const Resolved&, State&, Backend&);

  // Its declaration of `field`, or null when it does not write it.
  const FieldLayout* written(const std::string& field) const;
};

// Every stage kind, ties in the run order broken by this order: the tissue mesh's surface, then
// each effect's in the list's order (core/effects/effect_list.cpp).
const std::vector<StageKind>& stage_kinds();
// The kind that writes `field`, or null when none does.
const StageKind* stage_writing(const std::string& field);

// What a row says of a field: one value (of `channels` components) per pixel of the panel ...
FieldLayout image_field(const char* name, ElementType type, int channels, const char* unit, const char* description);
// ... or one row of elements (ring-buffer slots, or counters); `on_request`: written to files only
// when the scene lists it.
FieldLayout element_field(const char* name, ElementType type, int channels, bool on_request, const char* unit,
                          const char* description);
// An image field written to files only when the scene lists it: constants of the run.
FieldLayout on_request(FieldLayout field);
// Whether a scene declares the effect of P: a stage's `wanted` for the effect that calls for it.
template <class P>
bool declares(const Scene& scene) {
  return scene.effects.has<P>();
}
// A stage that reads no field.
std::vector<std::string> no_fields(const Scene&);

// How a row builds its stage S: S(kind, scene, resolved, state, backend).
template <class S>
std::unique_ptr<Stage> make_stage(const StageKind& kind, const Scene& scene, const Resolved& resolved, State& state,
                                  Backend& backend) {
  return std::make_unique<S>(kind, scene, resolved, state, backend);
}

}  // namespace bleedsim
