#pragma once
// Vessel density (docs/bleeding.md, "Vessels"): a map over the panel of how densely the mucosa is
// vascularised, 0 to 1; a cut bleeds in proportion to the map's mean along its wound.
#include <string>

#include "core/runtime/params.h"

namespace bleedsim {

// Present in a Scene only when the scene calls for vessel-driven bleeding; needs [particles].
struct VesselParams {
  std::string map = "procedural";  // the procedural tissue's own vessels, or a PNG file
};

const ParamTable<VesselParams>& vessel_table();

}  // namespace bleedsim
