#pragma once
// The haptic channel: one row per 1 kHz tick (core/haptics/haptics.h), as columns of one type each. The
// HDF5 writer stores each column as /haptics/<name> (docs/output-format.md) and the frame hash
// covers the same bytes, so goldens and GPU parity pin the haptics beside the frames.
#include <cstdint>
#include <string>
#include <vector>

#include "core/haptics/haptics.h"

namespace bleedsim {

struct HapticColumn {
  enum class Type { f64, u8 };
  const char* name;
  Type type;
  int components;  // values per tick: 1, 2 (panel x, y) or 3 (device x, y, z)
  const char* unit;
  const char* description;
  void (*values)(const HapticTick& tick, double* out);  // writes `components` values
};

// The columns, in the order they are written and hashed.
const std::vector<HapticColumn>& haptic_columns();

// One column's values for these ticks, tick after tick, as little-endian bytes of its type.
std::vector<std::uint8_t> haptic_column_bytes(const HapticColumn& column, const std::vector<HapticTick>& ticks);

// FNV-1a 64 over every column's bytes, in column order.
std::uint64_t haptic_channel_hash(const std::vector<HapticTick>& ticks);

}  // namespace bleedsim
