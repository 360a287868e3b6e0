// The trace loader (core/io/trace_csv.h) on any bytes, without repairs and with repairs of dropouts
// up to a second: it must refuse them with an InputError or accept them, never crash, overflow or
// read out of bounds. Its memory is capped at 64 MiB, as a small machine would cap it: past that it
// must refuse, not allocate.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/io/trace_csv.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  for (const double repair_s : {0.0, 1.0}) {
    try {
      bleedsim::parse_trace(text, "fuzzed.csv", bleedsim::TraceOptions{repair_s, std::size_t{64} << 20});
    } catch (const bleedsim::InputError&) {
    }
  }
  return 0;
}
