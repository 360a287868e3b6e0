// `import bleedsim`: scenarios and simulations from Python (docs/python.md).
#include <pybind11/pybind11.h>

#include "core/runtime/build_info.h"
#include "core/runtime/input_error.h"
#include "python/bindings.h"
#include "python/device_field.h"

PYBIND11_MODULE(bleedsim, module) {
  module.doc() =
      "bleedsim: bleeding effects for endoscopic sinus surgery simulation. Load a scenario, make a "
      "Simulation, step it and read its fields as NumPy arrays (docs/python.md).";
  module.attr("__version__") = bleedsim::version();
  // Bad input reads as the CLI's "file:line:column: key: message", as a ValueError.
  pybind11::register_exception<bleedsim::InputError>(module, "InputError", PyExc_ValueError);
  bleedsim::python::bind_scenario(module);
  bleedsim::python::bind_simulation(module);
  bleedsim::python::bind_device_field(module);
}
