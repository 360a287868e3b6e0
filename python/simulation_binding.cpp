// bleedsim.Simulation: a scenario's run, stepped from Python, its fields read in place as NumPy
// arrays.
#include <cstdint>
#include <memory>
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
#include "python/cut_keys.h"
#include "python/device_field.h"
#include "python/py_simulation.h"

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

std::unique_ptr<PySimulation> make(const Scenario& scenario, const std::string& backend, int threads,
                                   bool host_stylus) {
  auto made = std::make_unique<PySimulation>();
  const BackendChoice choice = backend_choice(backend, threads);
  made->cuda_device = choice.cuda_device;
  Scene scene = scenario.scene;
  // A file's [haptics] names a trace; the host drives the same stylus itself in its place.
  if (host_stylus) {
    if (!scene.haptics) throw py::value_error("host_stylus=True: this scene declares no [haptics], no stylus to drive");
    scene.trace.reset();
  }
  try {
    made->simulation = std::make_unique<Simulation>(std::move(scene), choice);
  } catch (const InputError& e) {
    throw scenario.placed(e);  // the memory check names the key that sets the size: point at its line
  }
  return made;
}

FieldView field_named(const Simulation& simulation, const std::string& name) {
  try {
    return simulation.field(name);
  } catch (const std::out_of_range&) {
    throw py::key_error("no field '" + name + "' in this scene (field_names() lists them)");
  }
}

// The field in place, keeping `self` (the Simulation) alive: a read-only NumPy view of host memory,
// or on the cuda backend a DeviceField for DLPack.
py::object field_in_place(py::object self, const std::string& name) {
  PySimulation& held = self.cast<PySimulation&>();
  const FieldView view = field_named(*held.simulation, name);
  if (view.location == BackendKind::cuda) return device_field(self, view, held.cuda_device);
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

// Each frame computed without the GIL; between frames, with it, `progress` is called and Ctrl-C
// (a pending signal) stops the loop.
void step(PySimulation& self, int frames, const py::object& progress) {
  if (frames < 0) throw py::value_error("step(frames): frames must be 0 or more");
  if (!progress.is_none() && !PyCallable_Check(progress.ptr()))
    throw py::type_error("step(progress=...): a callable, progress(done, frames), or None");
  for (int k = 0; k < frames; ++k) {
    {
      const auto lock = self.lock();
      py::gil_scoped_release release;
      self.simulation->step();
    }
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    if (!progress.is_none()) progress(k + 1, frames);
  }
}

void add_cut(PySimulation& self, double x_mm, double y_mm, double start_s, const py::kwargs& keys) {
  const auto lock = self.lock();
  self.simulation->add_cut(cut_from_keys(self.simulation->scene(), x_mm, y_mm, start_s, keys));
}

void add_stylus_sample(PySimulation& self, double t_s, double x_mm, double y_mm, bool contact, std::uint8_t buttons) {
  const auto lock = self.lock();
  self.simulation->add_stylus_sample(ToolSample{t_s, x_mm, y_mm, contact, buttons});
}

}  // namespace

py::dtype dtype_of(ElementType type) {
  switch (type) {
    case ElementType::u8: return py::dtype::of<std::uint8_t>();
    case ElementType::u32: return py::dtype::of<std::uint32_t>();
    case ElementType::u64: return py::dtype::of<std::uint64_t>();
    case ElementType::f32: return py::dtype::of<float>();
  }
  throw std::logic_error("unknown element type");
}

std::vector<py::ssize_t> shape_of(const FieldLayout& field) {
  std::vector<py::ssize_t> shape;
  if (field.image) shape.push_back(field.height);
  shape.push_back(field.width);
  if (field.channels > 1) shape.push_back(field.channels);
  return shape;
}

void bind_simulation(py::module_& module) {
  py::class_<PySimulation>(module, "Simulation",
                           "A run of a scenario's scene: step it one frame at a time and read its fields.")
      .def(py::init(&make), py::arg("scenario"), py::arg("backend") = "auto", py::arg("threads") = 0,
           py::kw_only(), py::arg("host_stylus") = false,
           "Makes the scenario's simulation on `backend`: \"auto\" (CUDA when a device is present), \"cpu\" "
           "or \"cuda\"; `threads`: the cpu backend's (0: one per hardware thread). The scene is copied: "
           "the Scenario stays as it was. host_stylus=True: the stylus of the scene's [haptics] is driven "
           "by add_stylus_sample() instead of its trace, which is not replayed (ValueError for a scene "
           "without [haptics]). A scene too large for memory raises bleedsim.InputError; a backend this "
           "build or machine lacks, RuntimeError.")
      .def("step", &step, py::arg("frames") = 1, py::kw_only(), py::arg("progress") = py::none(),
           "Computes the next `frames` frames, each without holding the GIL (other Python threads run "
           "meanwhile; calls on this Simulation from them wait for the frame). After each frame, "
           "progress(done, frames) is called when given (done: frames of this call computed so far), and "
           "Ctrl-C stops the loop (KeyboardInterrupt; the frames computed stay computed).")
      .def("add_cut", &add_cut, py::arg("x_mm"), py::arg("y_mm"), py::arg("start_s"),
           "A cut the host's tool made, as a [[cut]] table of a scenario gives one: at (x_mm, y_mm) on the "
           "panel (mm, x right, y down from its top-left corner), made at start_s (s); by name any other "
           "[[cut]] key (radius_mm, growth_per_s, wound_mm, flow_mm3_per_s_per_mm, bleed_s, clot_s, "
           "arterial, wound_angle_deg; docs/scenario-format.md), the scene's [spread] and [particles] "
           "defaults for those not given. The frames computed from then on show it from start_s. A value "
           "out of its range raises ValueError with the C++ API's message (\"cut.radius_mm: must be "
           "greater than 0 (got 0)\"); a key [[cut]] lacks or a value of the wrong type, TypeError.")
      .def("add_stylus_sample", &add_stylus_sample, py::arg("t_s"), py::arg("x_mm"), py::arg("y_mm"),
           py::arg("contact") = false, py::arg("buttons") = 0,
           "A sample of the host's stylus, for a scene with [haptics] and no trace: at t_s (s) its tip is at "
           "(x_mm, y_mm) on the panel, touching the tissue when `contact`, with the grip buttons `buttons` "
           "held (a bit each, 0 to 255). The instrument ([suction], [contact]) follows the samples in "
           "straight lines and stays at the last; give them up to the end of each frame before stepping "
           "it. ValueError (the C++ API's message) for a scene whose stylus is not the host's, a sample "
           "not later than the one before, or a value that is not finite.")
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
      .def("field", &field_in_place, py::arg("name"),
           "The field `name` where the backend keeps it, no copy. On cpu: a read-only NumPy array over the "
           "simulation's host memory, shaped (height, width[, channels]) for an image, (elements[, "
           "channels]) for a per-element array (a particle per slot). On cuda: a DeviceField over device "
           "memory, shaped alike, for DLPack (cupy.from_dlpack, torch.from_dlpack). Either holds the last "
           "computed frame's values until the next step(), which overwrites that memory in place: it then "
           "shows the new frame. Copy it (numpy.array(view), copy_field()) to keep a frame. It keeps the "
           "Simulation alive. KeyError for a name the scene lacks.")
      .def("copy_field", &field_copy, py::arg("name"),
           "A copy of the field `name` in a new, writable NumPy array, from either backend; shaped as field().")
      .def("frame_hash", &frame_hash,
           "The last computed frame's FNV-1a 64 hash of each field, {name: 16 hex digits}, in field order: "
           "what `bleedsim hash` prints on that frame's line.");
}

}  // namespace bleedsim::python
