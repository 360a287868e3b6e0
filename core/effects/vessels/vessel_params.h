#pragma once
// Vessel density (docs/bleeding.md, "Vessels"): a rule for how a cut bleeds. A map over the panel of
// how densely the mucosa is vascularised, 0 to 1 (Scene::vessel_density); a cut bleeds in proportion
// to the map's mean along its wound (core/bleeding/vessel_density.h), and with [pulse] a dense one
// is arterial.
#include <string>

#include "core/runtime/params.h"
#include "core/scene/scene.h"

namespace bleedsim {

template <class P>
struct Effect;

// Present in a Scene only when the scene calls for vessel-driven bleeding; needs [particles].
struct VesselParams {
  std::string map = "procedural";  // the procedural tissue's own vessels, or a PNG file
};

const ParamTable<VesselParams>& vessel_table();
const Effect<VesselParams>& vessel_effect();

// The cut as it bleeds in this scene: without [vessels], unchanged; with them, its vessel density
// is the map's mean along its wound, and, with [pulse] too, a wound reaching pulse.arterial_density
// is arterial.
Cut with_vessels(const Scene& scene, Cut cut);

}  // namespace bleedsim
