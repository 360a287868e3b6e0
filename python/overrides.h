#pragma once
// A dict of overrides ({"particles.diameter_mm": 0.1}) as the scenario reader's override lines
// ("particles.diameter_mm=0.1", core/io/scenario.h): each value written as TOML, so the reader
// checks it as it checks a file's.
#include <string>
#include <vector>

#include <pybind11/pybind11.h>

namespace bleedsim::python {

// Values are bool, int, float, str or lists of them; anything else is a TypeError naming the key.
std::vector<std::string> override_lines(const pybind11::dict& overrides);

}  // namespace bleedsim::python
