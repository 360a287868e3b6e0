// bleedsim.load_scenario, load_scenario_text and the Scenario they return.
#include <optional>
#include <string>

#include <pybind11/stl.h>

#include "core/io/scenario.h"
#include "python/bindings.h"
#include "python/overrides.h"

namespace bleedsim::python {
namespace py = pybind11;
namespace {

std::vector<std::string> lines_of(const std::optional<py::dict>& overrides) {
  return overrides ? override_lines(*overrides) : std::vector<std::string>{};
}

}  // namespace

void bind_scenario(py::module_& module) {
  py::class_<Scenario>(module, "Scenario",
                       "A scenario read and checked: its scene, and what its file said (Simulation(scenario) runs "
                       "a copy of the scene, so one Scenario makes any number of simulations).")
      .def_readonly("path", &Scenario::path, "The file it was read from (or the name given to its text).")
      .def_readonly("text", &Scenario::text, "The file's text, as written (without the overrides).")
      .def_property_readonly(
          "name", [](const Scenario& s) { return s.scene.name; }, "The scene's name ([scene].name).")
      .def_property_readonly(
          "frame_count", [](const Scenario& s) { return s.scene.frame_count(); },
          "The frames a run of it computes (duration × frame rate).");

  module.def(
      "load_scenario",
      [](const std::string& path, const std::optional<py::dict>& overrides) {
        return load_scenario(path, ReadTissue::draw, lines_of(overrides));
      },
      py::arg("path"), py::kw_only(), py::arg("overrides") = py::none(),
      "Reads and checks a scenario file (TOML, docs/scenario-format.md), as `bleedsim run` does.\n\n"
      "overrides: {\"table.key\": value} set over the file's values and checked as if written there "
      "(`bleedsim hash --set table.key=value`). Bad input raises bleedsim.InputError (a ValueError) "
      "whose message is the CLI's: \"file:line:column: key: message\", an override's place "
      "\"overrides:N:column\" with N its place in the dict.");
  module.def(
      "load_scenario_text",
      [](const std::string& text, const std::string& path, const std::optional<py::dict>& overrides) {
        return parse_scenario(text, path, ReadTissue::draw, lines_of(overrides));
      },
      py::arg("text"), py::kw_only(), py::arg("path") = "<text>", py::arg("overrides") = py::none(),
      "load_scenario for TOML text in memory; `path` names it in messages and anchors the relative "
      "paths it names (a trace, a mesh, a texture).");
}

}  // namespace bleedsim::python
