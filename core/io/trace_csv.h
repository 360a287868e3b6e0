#pragma once
// Recorded Novint Falcon stylus traces (docs/traces.md): a CSV with a metadata block, a header
// with explicit units and one sample per line, read and validated here. Every problem is an
// InputError that names the file, the line and the key; a short dropout may instead be repaired
// (TraceOptions::max_repair_gap_s), and each repair is described in Trace::repairs.
#include <string>

#include "core/haptics/trace.h"
#include "core/runtime/input_error.h"

namespace bleedsim {

struct TraceOptions {
  // A gap between two samples up to this long (seconds) is filled by linear interpolation at
  // the nominal rate instead of being refused; 0 repairs nothing.
  double max_repair_gap_s = 0;
};

// rate_hz must lie in this range: a sample rate near the Falcon's 1 kHz servo loop.
constexpr double kTraceMinRate_hz = 900, kTraceMaxRate_hz = 1100;

// Reads and validates a trace file; throws InputError on any problem.
Trace load_trace(const std::string& path, const TraceOptions& options = {});
// The same for text already in memory; `path` names it in messages.
Trace parse_trace(const std::string& text, const std::string& path, const TraceOptions& options = {});

}  // namespace bleedsim
