#pragma once
// The parts of the module, each adding its classes and functions (bleedsim_module.cpp calls them).
#include <pybind11/pybind11.h>

namespace bleedsim::python {

void bind_scenario(pybind11::module_& module);
void bind_simulation(pybind11::module_& module);

}  // namespace bleedsim::python
