#pragma once
// Recorded Novint Falcon stylus traces (docs/traces.md): a CSV with a metadata block, a header
// with explicit units and one sample per line, read and validated here. Every problem is an
// InputError that names the file, the line and the key; a short dropout may instead be repaired
// (TraceOptions::max_repair_gap_s), and each repair is described in Trace::repairs.
#include <cstddef>
#include <optional>
#include <string>

#include "core/runtime/input_error.h"
#include "core/runtime/memory.h"
#include "core/scene/trace.h"

namespace bleedsim {

struct TraceOptions {
  // A gap between two samples up to this long (seconds) is filled by linear interpolation at
  // the nominal rate instead of being refused; 0 repairs nothing.
  double max_repair_gap_s = 0;
  // The host memory the trace may take (none given: what available_host_memory() reports). The
  // file is sized from its lines before any is read, and its repairs before they are made.
  std::optional<std::size_t> memory_room;
};

// rate_hz must lie in this range: a sample rate near the Falcon's 1 kHz servo loop.
constexpr double kTraceMinRate_hz = 900, kTraceMaxRate_hz = 1100;

// Reads and validates a trace file, a line at a time; throws InputError on any problem. Its text
// may start with a UTF-8 byte-order mark; its lines end in LF or CR LF.
Trace load_trace(const std::string& path, const TraceOptions& options = {});
// The same for text already in memory; `path` names it in messages.
Trace parse_trace(const std::string& text, const std::string& path, const TraceOptions& options = {});

// The most host memory load_trace() takes for `path`, from a pass over its lines, under `key`.
MemoryPart trace_memory(const std::string& path, const std::string& key);

}  // namespace bleedsim
