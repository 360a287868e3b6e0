#pragma once
// Where a wound meets the vessels (docs/bleeding.md, "Vessels"): the mean of the scene's vessel
// density along a cut's wound sets how hard it bleeds, and, with a pulse, whether it is arterial.
#include "core/scene/scene.h"

namespace bleedsim {

// The mean of the density map along the segment (x0, y0)–(x1, y1) in mm: the map read bilinearly
// between pixel centres (held flat beyond the outermost ones), averaged by the midpoint rule over
// steps of at most a quarter pixel — exact for a map that varies linearly. A segment of no length
// reads the one point.
double mean_vessel_density(const Scene& scene, double x0_mm, double y0_mm, double x1_mm, double y1_mm);

// The cut as it bleeds in this scene: without [vessels], unchanged; with them, its vessel density
// is the map's mean along its wound (wound_mm long, centred on the cut, at wound_angle_deg), and,
// with [pulse] too, a wound reaching pulse.arterial_density is arterial.
Cut with_vessels(const Scene& scene, Cut cut);

}  // namespace bleedsim
