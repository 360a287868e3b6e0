#pragma once
// Recorded Novint Falcon stylus traces (docs/traces.md): a CSV with a metadata block, a header
// with explicit units and one sample per line, read a line at a time and validated here. Every
// problem is an InputError that names the file, the line and the key; a short dropout may instead be
// repaired (TraceOptions::max_repair_gap_s), and each repair is described in Trace::repairs.
#include <cstddef>
#include <functional>
#include <limits>
#include <optional>
#include <string>

#include "core/runtime/input_error.h"
#include "core/runtime/input_file.h"
#include "core/runtime/memory.h"
#include "core/scene/trace.h"

namespace bleedsim {

struct TraceOptions {
  // A gap between two samples up to this long (seconds) is filled by linear interpolation at
  // the nominal rate instead of being refused; 0 repairs nothing.
  double max_repair_gap_s = 0;
  // The host memory the samples kept may take (none given: what available_host_memory() reports),
  // checked before their store grows.
  std::optional<std::size_t> memory_room;
  // The samples kept are those up to the first one more than this long (seconds) after the first
  // sample: a run's last haptic tick. The lines after it are not read, so not checked.
  double keep_s = std::numeric_limits<double>::infinity();
};

// rate_hz must lie in this range: a sample rate near the Falcon's 1 kHz servo loop.
constexpr double kTraceMinRate_hz = 900, kTraceMaxRate_hz = 1100;
// The rate is measured over the first this many intervals read (ten seconds at 1 kHz): a
// recording's rate is its device's, and a gap past them is still found, interval by interval.
constexpr std::size_t kTraceRateWindow = 10000;
// The longest line a trace may have: a metadata line, the header or a sample. What the reader holds
// beside the samples it keeps is bounded by it: a line, the metadata (at most 1000 keys), the
// intervals the rate is measured over, and the first kTraceRepairsDescribed repairs' descriptions.
constexpr std::size_t kTraceMaxLineBytes = 4096;
constexpr std::size_t kTraceRepairsDescribed = 100;

// A sample as it is read, repairs included, in time order; false when no more is wanted (the lines
// after it are then not read).
using TakeSample = std::function<bool(const TraceSample&)>;

// Reads a trace a line at a time and checks it, handing each sample to `take`; throws InputError on
// any problem, naming the file, the line and the key (the file's key and place for its memory). Its
// text may start with a UTF-8 byte-order mark; its lines end in LF or CR LF. The metadata, the rate,
// the repairs and the measured interval come back; the samples are what `take` kept of them.
Trace read_trace(const InputFile& file, const TraceOptions& options, const TakeSample& take);

// The samples kept (options.keep_s), in a store whose every growth is counted first against the room.
Trace load_trace(const InputFile& file, const TraceOptions& options = {});
// The same for text already in memory; `path` names it in messages.
Trace parse_trace(const std::string& text, const std::string& path, const TraceOptions& options = {});

// The host memory the samples of a loaded trace take, under the file's key: what validate counts.
MemoryPart trace_memory(const Trace& trace, const InputFile& file);

}  // namespace bleedsim
