#pragma once
// An effect's row in the one list of effects (core/effects/effect_list.h): its table, and what it
// adds to a scene that declares it, by kind (docs/architecture.md, "Adding an effect"):
//   a stage      the pipeline runs it each frame (Effect::stages);
//   a hook       the particle step calls it after each sub-step (Effect::hooks);
//   a rule       for how a cut bleeds: its math in core/bleeding/, applied to each cut as it is made
//                (Effect::as_made) or read from its parameters where the blood is counted.
// Everything else that enumerates effects reads the list: the scene's check, the scenario reader,
// `bleedsim validate` and `params`, the docs' tables, the resolution of derived settings.
#include <cstdint>
#include <string>
#include <vector>

#include "core/effects/particle_hook.h"
#include "core/effects/resolved.h"
#include "core/effects/stage_kinds.h"
#include "core/runtime/params.h"
#include "core/scene/scene.h"

namespace bleedsim {

// What `bleedsim validate` knows of a run before it runs: the cuts it will make (the scene's, as
// made, and a stand-in for each the stylus' trace makes), with which an effect may say what a run
// of them would do.
struct RunOutline {
  std::vector<Cut> cuts;
};

template <class P>
struct Effect {
  using Params = P;
  const ParamTable<P>& (*table)();
  std::vector<StageKind> stages = {};
  std::vector<HookKind> hooks = {};
  // A rule: the cut as it bleeds in a scene that declares this effect, from the cut as given.
  Cut (*as_made)(const Scene&, Cut) = nullptr;
  // Its settings, resolved once per scene into `resolved` (after the effects before it in the list).
  void (*resolve)(const Scene&, Resolved&) = nullptr;
  // What `bleedsim validate` says of it: whole lines, or "".
  std::string (*describe)(const Scene&, const Resolved&, const RunOutline&) = nullptr;
};

}  // namespace bleedsim
