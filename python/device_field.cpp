#include "python/device_field.h"

#include <cstdint>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <pybind11/stl.h>

#include "python/dlpack.h"
#include "python/py_simulation.h"

namespace bleedsim::python {
namespace py = pybind11;
namespace {

struct DeviceField {
  py::object simulation;  // the PySimulation whose memory it is
  const Field* field;
  void* data;
  int device;
};

// What an exported tensor holds: its shape and strides, and a reference to the Simulation, so that
// the memory outlives every tensor made from it.
struct Export {
  PyObject* simulation;
  std::vector<std::int64_t> shape;
  std::vector<std::int64_t> strides;
};

dlpack::DLDataType dl_type(ElementType type) {
  switch (type) {
    case ElementType::u8: return {dlpack::kDLUInt, 8, 1};
    case ElementType::u32: return {dlpack::kDLUInt, 32, 1};
    case ElementType::u64: return {dlpack::kDLUInt, 64, 1};
    case ElementType::f32: return {dlpack::kDLFloat, 32, 1};
  }
  throw std::logic_error("unknown element type");
}

// Called by the consumer when its tensor goes, from any thread, holding the GIL or not.
template <class Managed>
void release(Managed* managed) {
  auto* exported = static_cast<Export*>(managed->manager_ctx);
  if (Py_IsInitialized()) {
    const PyGILState_STATE state = PyGILState_Ensure();
    Py_DECREF(exported->simulation);
    PyGILState_Release(state);
  }
  delete exported;
  delete managed;
}

template <class Managed>
constexpr const char* unused_name() {
  return std::is_same_v<Managed, dlpack::DLManagedTensor> ? "dltensor" : "dltensor_versioned";
}

// The capsule's own end: one that no consumer took (a consumer renames it "used_...") still owns
// its tensor.
template <class Managed>
void capsule_gone(PyObject* capsule) {
  if (!PyCapsule_IsValid(capsule, unused_name<Managed>())) return;
  auto* managed = static_cast<Managed*>(PyCapsule_GetPointer(capsule, unused_name<Managed>()));
  managed->deleter(managed);
}

template <class Managed>
py::object capsule(const DeviceField& self) {
  auto* exported = new Export{self.simulation.ptr(), {}, {}};
  for (const py::ssize_t extent : shape_of(*self.field)) exported->shape.push_back(extent);
  exported->strides.assign(exported->shape.size(), 1);
  for (std::size_t i = exported->shape.size() - 1; i > 0; --i)
    exported->strides[i - 1] = exported->strides[i] * exported->shape[i];
  auto* managed = new Managed{};
  managed->dl_tensor = {self.data,
                        {dlpack::kDLCUDA, self.device},
                        std::int32_t(exported->shape.size()),
                        dl_type(self.field->type),
                        exported->shape.data(),
                        exported->strides.data(),
                        0};
  managed->manager_ctx = exported;
  managed->deleter = &release<Managed>;
  if constexpr (std::is_same_v<Managed, dlpack::DLManagedTensorVersioned>) {
    managed->version = {1, 0};
    managed->flags = dlpack::kReadOnly;
  }
  PyObject* made = PyCapsule_New(managed, unused_name<Managed>(), &capsule_gone<Managed>);
  if (!made) {
    delete exported;
    delete managed;
    throw py::error_already_set();
  }
  Py_INCREF(exported->simulation);
  return py::reinterpret_steal<py::object>(made);
}

// The DLPack protocol's producer side (data-apis.org's array API, __dlpack__): the field in place,
// read-only, once the device has finished the frame.
py::object to_dlpack(const DeviceField& self, const py::object& stream, const py::object& max_version,
                     const py::object& dl_device, const py::object& copy) {
  if (!copy.is_none() && copy.cast<bool>())
    throw py::buffer_error("__dlpack__(copy=True): a field is handed over in place only (copy_field() copies it "
                           "to the host)");
  if (!dl_device.is_none()) {
    const auto wanted = dl_device.cast<std::pair<int, int>>();
    if (wanted != std::pair<int, int>{dlpack::kDLCUDA, self.device})
      throw py::buffer_error("__dlpack__(dl_device=...): the field is on CUDA device " + std::to_string(self.device));
  }
  // stream -1: the consumer asks for no synchronisation. Any other waits for the whole device,
  // which serves every stream the consumer may read on.
  if (stream.is_none() || stream.cast<long long>() != -1) {
    PySimulation& simulation = self.simulation.cast<PySimulation&>();
    const auto lock = simulation.lock();
    py::gil_scoped_release release;
    simulation.simulation->synchronize();
  }
  const bool versioned = !max_version.is_none() && max_version.cast<std::pair<int, int>>().first >= 1;
  return versioned ? capsule<dlpack::DLManagedTensorVersioned>(self) : capsule<dlpack::DLManagedTensor>(self);
}

}  // namespace

py::object device_field(py::object simulation, const FieldView& view, int device) {
  return py::cast(DeviceField{std::move(simulation), view.field, const_cast<void*>(view.data), device});
}

void bind_device_field(py::module_& module) {
  py::class_<DeviceField>(module, "DeviceField",
                          "A field in a cuda Simulation's device memory, for DLPack consumers: "
                          "cupy.from_dlpack(field), torch.from_dlpack(field) read it in place, no copy. Read-only "
                          "(a versioned DLPack capsule says so; the legacy capsule, for consumers that ask for no "
                          "version, cannot: do not write through it). Like field()'s NumPy views it holds the last "
                          "computed frame until the next step(), which overwrites that memory; it and every tensor "
                          "made from it keep the Simulation alive.")
      .def("__dlpack__", &to_dlpack, py::kw_only(), py::arg("stream") = py::none(),
           py::arg("max_version") = py::none(), py::arg("dl_device") = py::none(), py::arg("copy") = py::none(),
           "A DLPack capsule of the field (DLPack 1.0 \"dltensor_versioned\", flagged read-only, when max_version "
           "allows; else the legacy \"dltensor\"). Waits for the device to finish the frame unless stream is -1. "
           "copy=True raises BufferError: the field is handed over in place only.")
      .def(
          "__dlpack_device__", [](const DeviceField& self) { return py::make_tuple(dlpack::kDLCUDA, self.device); },
          "(2, device): kDLCUDA and the CUDA device the Simulation runs on.")
      .def_property_readonly(
          "name", [](const DeviceField& self) { return self.field->name; }, "The field's name.")
      .def_property_readonly(
          "shape", [](const DeviceField& self) { return py::tuple(py::cast(shape_of(*self.field))); },
          "Shaped as field() on the cpu backend: (height, width[, channels]) or (elements[, channels]).")
      .def_property_readonly(
          "dtype", [](const DeviceField& self) { return dtype_of(self.field->type); }, "Its NumPy dtype.")
      .def("__repr__", [](const DeviceField& self) {
        return "<bleedsim.DeviceField '" + self.field->name + "' " + std::string(py::str(py::cast(shape_of(*self.field)))) +
               " " + std::string(py::str(dtype_of(self.field->type))) + " on cuda:" + std::to_string(self.device) + ">";
      });
}

}  // namespace bleedsim::python
