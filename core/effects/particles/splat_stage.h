#pragma once
// The splat: the particles' film of blood (report §2.2.2.4), the particle effect's second stage.
#include "core/effects/stage_kinds.h"

namespace bleedsim {

// Its kind: the particle effect's second stage (particle_effect()).
const StageKind& splat_stage_kind();

}  // namespace bleedsim
