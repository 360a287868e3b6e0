#include "python/cut_keys.h"

#include <stdexcept>
#include <string>
#include <type_traits>
#include <variant>

#include "core/effects/cuts.h"
#include "core/runtime/params_impl.h"

namespace bleedsim::python {
namespace py = pybind11;
namespace {

// The keys add_cut() takes by name: the table's, less the three it takes first.
std::string optional_keys() {
  std::string keys;
  for (const Param<Cut>& param : cut_table().params) {
    const std::string key = param.key;
    if (key != "x_mm" && key != "y_mm" && key != "start_s") keys += (keys.empty() ? "" : ", ") + key;
  }
  return keys;
}

std::string type_name(const py::handle& value) { return py::str(py::type::of(value).attr("__name__")); }

}  // namespace

Cut cut_from_keys(const Scene& scene, double x_mm, double y_mm, double start_s, const py::kwargs& keys) {
  Cut cut = cut_at(scene, x_mm, y_mm, start_s);
  for (const auto& [name, value] : keys) {
    const std::string key = py::str(name);
    const Param<Cut>* param = nullptr;
    try {
      param = &param_named(cut_table(), key);
    } catch (const std::out_of_range&) {
      throw py::type_error("add_cut(): [[cut]] has no key '" + key + "' (by name: " + optional_keys() + ")");
    }
    std::visit(
        [&](auto field) {
          using F = decltype(field);
          // bool before numbers: Python's bool is an int, and a flag is no number.
          if constexpr (std::is_same_v<F, bool& (*)(Cut&)>) {
            if (!py::isinstance<py::bool_>(value))
              throw py::type_error("add_cut(): " + key + " is True or False, not " + type_name(value));
            field(cut) = value.cast<bool>();
          } else if constexpr (std::is_same_v<F, double& (*)(Cut&)>) {
            if (py::isinstance<py::bool_>(value) || !(py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value)))
              throw py::type_error("add_cut(): " + key + " is a number, not " + type_name(value));
            field(cut) = value.cast<double>();
          } else {
            throw std::logic_error("[[cut]] key " + key + " is neither a number nor a flag");
          }
        },
        param->field);
  }
  return cut;
}

}  // namespace bleedsim::python
