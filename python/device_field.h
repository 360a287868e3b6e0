#pragma once
// A field in a cuda Simulation's device memory, handed over in place through DLPack (__dlpack__,
// __dlpack_device__): cupy.from_dlpack(field), torch.from_dlpack(field) (docs/python.md).
#include <pybind11/pybind11.h>

#include "core/simulation/simulation.h"

namespace bleedsim::python {

// The field `view` of `simulation` (a PySimulation on the cuda backend, running on `device`),
// which it keeps alive.
pybind11::object device_field(pybind11::object simulation, const FieldView& view, int device);

void bind_device_field(pybind11::module_& module);

}  // namespace bleedsim::python
