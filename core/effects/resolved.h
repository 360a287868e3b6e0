#pragma once
// What a scene's effects resolve to, once per scene: the settings derived from their parameters
// (the particle model's constants, sub-steps and steps a second, the splat's radius, the tip's body,
// the suction's quota), each effect's its own type, held by type. Every consumer reads these: the
// stages, the hooks, the memory estimate, `bleedsim validate`, the study. Each effect's row says how
// it resolves (Effect::resolve); resolve() runs them in the list's order, so an effect may read what
// the effects before it resolved.
#include "core/runtime/type_map.h"
#include "core/scene/scene.h"

namespace bleedsim {

struct Resolved : TypeMap {};

// Every declared effect's settings (core/effects/effect_list.cpp).
Resolved resolve(const Scene& scene);

}  // namespace bleedsim
