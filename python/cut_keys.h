#pragma once
// A cut given from Python as a [[cut]] table's keys (Simulation.add_cut(x_mm, y_mm, start_s,
// radius_mm=..., ...)): what it leaves out is the scene's, as for a cut in a file (cut_at).
#include <pybind11/pybind11.h>

#include "core/scene/cut.h"
#include "core/scene/scene.h"

namespace bleedsim::python {

// A key no [[cut]] table has, or a value of the wrong type, is a TypeError naming the key; the
// values themselves are Simulation::add_cut's to check.
Cut cut_from_keys(const Scene& scene, double x_mm, double y_mm, double start_s, const pybind11::kwargs& keys);

}  // namespace bleedsim::python
