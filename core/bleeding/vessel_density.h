#pragma once
// Where a wound meets the vessels (docs/bleeding.md, "Vessels"): the mean of the scene's vessel
// density map along a cut's wound sets how hard it bleeds, and, with a pulse, whether it is arterial
// (with_vessels, core/effects/vessels/vessel_params.h, applies it to a cut).
#include "core/scene/scene.h"

namespace bleedsim {

// The mean of the density map along the segment (x0, y0)–(x1, y1) in mm: the map read bilinearly
// between pixel centres (held flat beyond the outermost ones), averaged by the midpoint rule over
// steps of at most a quarter pixel — exact for a map that varies linearly. A segment of no length
// reads the one point.
double mean_vessel_density(const Scene& scene, double x0_mm, double y0_mm, double x1_mm, double y1_mm);

// The mean along a cut's wound: wound_mm long, centred on the cut, at wound_angle_deg.
double wound_vessel_density(const Scene& scene, const Cut& cut);

}  // namespace bleedsim
