#pragma once
// A field of a Simulation, copied to the host as values of its element type.
#include <cstring>
#include <vector>

#include "core/simulation/simulation.h"

namespace bleedsim::test {

template <class T>
std::vector<T> field_values(const Simulation& sim, const char* name) {
  const std::vector<std::uint8_t> bytes = sim.copy_field(name);
  std::vector<T> values(bytes.size() / sizeof(T));
  std::memcpy(values.data(), bytes.data(), values.size() * sizeof(T));
  return values;
}

}  // namespace bleedsim::test
