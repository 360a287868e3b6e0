#pragma once
// The Simulation as the module holds it, shared by its bindings (simulation_binding.cpp) and the
// device fields it hands out (device_field.cpp).
#include <memory>
#include <mutex>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "core/simulation/simulation.h"

namespace bleedsim::python {

// The Simulation and a lock: step() runs without the GIL, so another Python thread may call in
// meanwhile; what reads or changes the fields waits for the frame.
struct PySimulation {
  std::unique_ptr<Simulation> simulation;
  int cuda_device = 0;  // the device a cuda backend runs on
  std::mutex busy;

  // Waits for the lock without the GIL, so that the thread stepping can finish; a free lock is taken
  // keeping the GIL, which step() then lets go of only while the frame computes.
  std::unique_lock<std::mutex> lock() {
    std::unique_lock<std::mutex> held(busy, std::try_to_lock);
    if (!held.owns_lock()) {
      pybind11::gil_scoped_release release;
      held.lock();
    }
    return held;
  }
};

// (height, width[, channels]) for an image, (width[, channels]) for a per-element array.
std::vector<pybind11::ssize_t> shape_of(const FieldLayout& field);
pybind11::dtype dtype_of(ElementType type);

}  // namespace bleedsim::python
