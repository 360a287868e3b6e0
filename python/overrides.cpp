#include "python/overrides.h"

#include <cstdio>

namespace bleedsim::python {
namespace py = pybind11;
namespace {

// A TOML basic string: quotes, backslashes and control characters escaped, so the value is one
// line whatever it holds.
std::string toml_string(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\u%04x", unsigned(static_cast<unsigned char>(c)));
      out += escaped;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string toml_value(const py::handle& value, const std::string& key) {
  // bool before int: Python's bool is an int.
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::int_>(value)) return py::str(value);
  // repr: the shortest text that reads back as the same double, and TOML's inf and nan.
  if (py::isinstance<py::float_>(value)) return py::repr(value);
  if (py::isinstance<py::str>(value)) return toml_string(value.cast<std::string>());
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    std::string out = "[";
    for (const py::handle& item : value) out += (out.size() > 1 ? ", " : "") + toml_value(item, key);
    return out + "]";
  }
  throw py::type_error("override " + key + ": a value is bool, int, float, str or a list of them, not " +
                       std::string(py::str(py::type::of(value).attr("__name__"))));
}

}  // namespace

std::vector<std::string> override_lines(const py::dict& overrides) {
  std::vector<std::string> lines;
  for (const auto& [key, value] : overrides) {
    if (!py::isinstance<py::str>(key)) throw py::type_error("an override's key is a str, \"table.key\"");
    const std::string name = key.cast<std::string>();
    lines.push_back(name + "=" + toml_value(value, name));
  }
  return lines;
}

}  // namespace bleedsim::python
