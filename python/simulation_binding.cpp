// bleedsim.Simulation: a scenario's run, stepped from Python, its fields read in place as NumPy
// arrays.
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "core/io/scenario.h"
#include "core/runtime/hash.h"
#include "core/simulation/frame_hash.h"
#include "core/simulation/simulation.h"
#include "python/bindings.h"

namespace bleedsim::python {
namespace py = pybind11;
namespace {

BackendChoice backend_choice(const std::string& name, int threads) {
  if (name != "auto" && name != "cpu" && name != "cuda")
    throw py::value_error("backend: auto, cpu or cuda (got '" + name + "')");
  const BackendChoice::Want want = name == "cpu"    ? BackendChoice::Want::cpu
                                   : name == "cuda" ? BackendChoice::Want::cuda
                                                    : BackendChoice::Want::automatic;
  return BackendChoice{want, threads};
}

// The Simulation and a lock: step() runs without the GIL, so another Python thread may call in
// meanwhile; what reads or changes the fields waits for the frame.
struct PySimulation {
  std::unique_ptr<Simulation> simulation;
  std::mutex busy;

  // Waits for the lock without the GIL, so that the thread stepping can finish.
  std::unique_lock<std::mutex> lock() {
    py::gil_scoped_release release;
    return std::unique_lock<std::mutex>(busy);
  }
};

std::unique_ptr<PySimulation> make(const Scenario& scenario, const std::string& backend, int threads) {
  auto made = std::make_unique<PySimulation>();
  try {
    made->simulation = std::make_unique<Simulation>(scenario.scene, backend_choice(backend, threads));
  } catch (const InputError& e) {
    throw scenario.placed(e);  // the memory check names the key that sets the size: point at its line
  }
  return made;
}

py::dtype dtype_of(ElementType type) {
  switch (type) {
    case ElementType::u8: return py::dtype::of<std::uint8_t>();
    case ElementType::u32: return py::dtype::of<std::uint32_t>();
    case ElementType::u64: return py::dtype::of<std::uint64_t>();
    case ElementType::f32: return py::dtype::of<float>();
  }
  throw std::logic_error("unknown element type");
}

// (height, width[, channels]) for an image, (width[, channels]) for a per-element array.
std::vector<py::ssize_t> shape_of(const FieldLayout& field) {
  std::vector<py::ssize_t> shape;
  if (field.image) shape.push_back(field.height);
  shape.push_back(field.width);
  if (field.channels > 1) shape.push_back(field.channels);
  return shape;
}

FieldView field_named(const Simulation& simulation, const std::string& name) {
  try {
    return simulation.field(name);
  } catch (const std::out_of_range&) {
    throw py::key_error("no field '" + name + "' in this scene (field_names() lists them)");
  }
}

// A read-only view of the field's host memory, keeping `self` (the Simulation) alive.
py::array field_view(py::object self, const std::string& name) {
  const Simulation& simulation = *self.cast<PySimulation&>().simulation;
  const FieldView view = field_named(simulation, name);
  if (view.location != BackendKind::cpu)
    throw std::runtime_error("field('" + name + "'): the " + to_string(view.location) +
                             " backend keeps its fields in device memory; copy_field() copies one to the host");
  py::array array(dtype_of(view.field->type), shape_of(*view.field), {}, view.data, self);
  array.attr("setflags")(py::arg("write") = false);
  return array;
}

py::array field_copy(PySimulation& self, const std::string& name) {
  const auto lock = self.lock();
  const Field& field = *field_named(*self.simulation, name).field;
  py::array array(dtype_of(field.type), shape_of(field));
  self.simulation->copy_field(name, array.mutable_data());
  return array;
}

py::dict frame_hash(PySimulation& self) {
  const auto lock = self.lock();
  if (self.simulation->frames_done() == 0) throw std::runtime_error("frame_hash(): no frame yet (step() first)");
  py::dict hashes;
  for (const auto& [name, hash] : hash_fields(*self.simulation)) hashes[py::str(name)] = hex64(hash);
  return hashes;
}

void step(PySimulation& self, int frames) {
  if (frames < 0) throw py::value_error("step(frames): frames must be 0 or more");
  const auto lock = self.lock();
  py::gil_scoped_release release;
  for (int k = 0; k < frames; ++k) self.simulation->step();
}

}  // namespace

void bind_simulation(py::module_& module) {
  py::class_<PySimulation>(module, "Simulation",
                           "A run of a scenario's scene: step it one frame at a time and read its fields.")
      .def(py::init(&make), py::arg("scenario"), py::arg("backend") = "auto", py::arg("threads") = 0,
           "Makes the scenario's simulation on `backend`: \"auto\" (CUDA when a device is present), \"cpu\" "
           "or \"cuda\"; `threads`: the cpu backend's (0: one per hardware thread). The scene is copied: "
           "the Scenario stays as it was. A scene too large for memory raises bleedsim.InputError; a "
           "backend this build or machine lacks, RuntimeError.")
      .def("step", &step, py::arg("frames") = 1,
           "Computes the next `frames` frames, without holding the GIL (other Python threads run "
           "meanwhile; calls on this Simulation from them wait for it).")
      .def_property_readonly(
          "frames_done", [](const PySimulation& s) { return s.simulation->frames_done(); },
          "Frames computed so far; the next step() computes frame number frames_done.")
      .def_property_readonly(
          "frame_count", [](const PySimulation& s) { return s.simulation->scene().frame_count(); },
          "The frames the scene's duration holds (step() may go past them).")
      .def_property_readonly(
          "time_s", [](const PySimulation& s) { return s.simulation->time_s(); },
          "Simulated time of the last computed frame, in seconds; 0 before the first.")
      .def_property_readonly(
          "backend", [](const PySimulation& s) { return to_string(s.simulation->backend().kind()); },
          "\"cpu\" or \"cuda\": the backend it runs on.")
      .def("field_names", [](const PySimulation& s) { return s.simulation->field_names(); },
           "The fields this scene produces (\"frame\" always), in the order its stages make them.")
      .def("field", &field_view, py::arg("name"),
           "The field `name` as a read-only NumPy array over the simulation's host memory, no copy: "
           "shaped (height, width[, channels]) for an image, (elements[, channels]) for a per-element "
           "array (a particle per slot). It holds the last computed frame's values until the next "
           "step(), which overwrites that memory in place: the array then shows the new frame. Copy "
           "it (numpy.array(view)) to keep a frame. The array keeps the Simulation alive. cpu backend "
           "only (RuntimeError on cuda: use copy_field). KeyError for a name the scene lacks.")
      .def("copy_field", &field_copy, py::arg("name"),
           "A copy of the field `name` in a new, writable NumPy array, from either backend; shaped as field().")
      .def("frame_hash", &frame_hash,
           "The last computed frame's FNV-1a 64 hash of each field, {name: 16 hex digits}, in field order: "
           "what `bleedsim hash` prints on that frame's line.");
}

}  // namespace bleedsim::python
