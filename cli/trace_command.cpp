// bleedsim trace info: what a recorded Falcon trace holds, after the loader has checked it, read a
// line at a time in the same memory whatever its length.
// bleedsim trace synth: a synthetic trace written to a file, whole or not at all.
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "cli/commands.h"
#include "core/io/trace_csv.h"
#include "core/io/trace_synth.h"

namespace bleedsim::cli {
namespace {

// What `trace info` says of a trace's samples, gathered as they are read: none is kept, so a trace
// of any length is described in the same memory.
class SampleTally {
 public:
  // The cuts listed by their times; past them, only counted.
  static constexpr std::size_t kPressesListed = 100;

  // The stretches during which the cutting button (0x1) is held.
  struct Press {
    double start_s, end_s;
  };

  void add(const TraceSample& s) {
    if (samples_++ == 0) first_s_ = s.t_s;
    last_s_ = s.t_s;
    const double at[] = {s.x_m, s.y_m, s.z_m};
    for (int axis = 0; axis < 3; ++axis) {
      low_m_[axis] = std::min(low_m_[axis], at[axis]);
      high_m_[axis] = std::max(high_m_[axis], at[axis]);
    }
    const bool held = s.buttons & 0x1;
    if (held && !held_) press_ = {s.t_s, s.t_s};
    if (held) press_.end_s = s.t_s;
    if (!held && held_) end_press();
    held_ = held;
  }

  void finish() {
    if (held_) end_press();
    held_ = false;
  }

  std::uint64_t samples() const { return samples_; }
  double first_s() const { return first_s_; }
  double last_s() const { return last_s_; }
  // "-10.0 to 10.0 mm" along axis 0, 1 or 2 (x, y, z).
  std::string range(int axis) const {
    char text[64];
    std::snprintf(text, sizeof text, "%.1f to %.1f mm", 1000.0 * low_m_[axis], 1000.0 * high_m_[axis]);
    return text;
  }
  std::uint64_t presses() const { return presses_; }
  const std::vector<Press>& listed() const { return listed_; }

 private:
  void end_press() {
    ++presses_;
    if (listed_.size() < kPressesListed) listed_.push_back(press_);
  }

  std::uint64_t samples_ = 0;
  double first_s_ = 0, last_s_ = 0;
  double low_m_[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, high_m_[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  bool held_ = false;
  Press press_{0, 0};
  std::uint64_t presses_ = 0;
  std::vector<Press> listed_;
};

namespace fs = std::filesystem;

// "x0,y0,x1,y1" in mm, and optionally the buttons held (",2"), as --stroke takes it; the buttons'
// range is synthesize_trace's to check.
StrokeSpec parse_stroke(const std::string& text) {
  std::vector<double> values;
  for (std::size_t begin = 0;;) {
    const std::size_t comma = text.find(',', begin);
    const std::string field = text.substr(begin, comma == std::string::npos ? comma : comma - begin);
    char* end = nullptr;
    values.push_back(std::strtod(field.c_str(), &end));
    if (field.empty() || *end != '\0' || !std::isfinite(values.back())) break;
    if (comma == std::string::npos) {
      if (values.size() == 4) return {values[0], values[1], values[2], values[3]};
      if (values.size() == 5 && values[4] == std::floor(values[4]) && std::abs(values[4]) < 1e6)
        return {values[0], values[1], values[2], values[3], int(values[4])};
      break;
    }
    begin = comma + 1;
  }
  throw InputError(SourcePlace{}, "--stroke",
                   "expected x0,y0,x1,y1[,buttons]: four numbers of mm and optionally the buttons held (an integer), "
                   "comma-separated (got '" + text + "')");
}

// The text as the loader reads it. What the loader refuses here is a fault of the generator, not
// bad input: it fails (exit 1) rather than blaming an option.
Trace read_back(const std::string& text, const std::string& path) {
  try {
    return parse_trace(text, path);
  } catch (const InputError& e) {
    throw std::runtime_error(std::string("the synthesised trace does not read back: ") + e.what());
  }
}

void refuse_out(const std::string& path, const std::string& message) {
  throw InputError(SourcePlace{path, 0, 0}, "--out", message);
}

// --out names a file; one that exists already is replaced only with --force.
void check_out(const std::string& path, bool force) {
  if (path.empty()) refuse_out(path, "must not be empty");
  std::error_code ec;
  const fs::file_status status = fs::symlink_status(path, ec);
  if (fs::is_directory(status)) refuse_out(path, "is a folder; name the trace file to write");
  if (fs::exists(status) && !force) refuse_out(path, "exists already; pass --force to overwrite it");
}

// Through FILE.partial and a rename, so that FILE is either the whole trace or untouched.
void write_whole(const std::string& path, const std::string& text) {
  const std::string partial = path + ".partial";
  errno = 0;
  std::ofstream out(partial, std::ios::binary | std::ios::trunc);
  if (!out) refuse_out(path, "cannot write '" + partial + "': " + std::strerror(errno ? errno : ENOENT));
  out << text;
  out.close();
  std::error_code ec, ignored;
  if (!out) {
    fs::remove(partial, ignored);
    refuse_out(path, "cannot write '" + partial + "' (is the disk full?)");
  }
  fs::rename(partial, path, ec);
  if (ec) {
    fs::remove(partial, ignored);
    refuse_out(path, "cannot rename '" + partial + "' to it: " + ec.message());
  }
}

}  // namespace

int trace_info_command(const std::string& path, double max_repair_gap_ms) {
  SampleTally tally;
  const Trace trace = read_trace(InputFile{path, "trace file"}, TraceOptions{max_repair_gap_ms / 1000.0, {}},
                                 [&tally](const TraceSample& s) {
                                   tally.add(s);
                                   return true;
                                 });
  tally.finish();
  const double interval = trace.median_interval_s;
  std::printf("%s: valid\n", path.c_str());
  std::printf("  device     %s\n", trace.metadata.count("device") ? trace.metadata.at("device").c_str() : "");
  std::printf("  samples    %llu over %.3f s (t = %.4f to %.4f s)\n", static_cast<unsigned long long>(tally.samples()),
              tally.last_s() - tally.first_s(), tally.first_s(), tally.last_s());
  std::printf("  rate       %g Hz stated, %.1f Hz measured (median interval %.4f ms)\n", trace.rate_hz,
              interval > 0 ? 1.0 / interval : 0.0, 1000.0 * interval);
  std::printf("  workspace  x %s, y %s, z %s\n", tally.range(0).c_str(), tally.range(1).c_str(), tally.range(2).c_str());
  std::printf("  force      %s\n", trace.has_force ? "recorded (fx_N, fy_N, fz_N)" : "not recorded");
  std::printf("  cuts       %llu (button 0x1 held)", static_cast<unsigned long long>(tally.presses()));
  for (const SampleTally::Press& p : tally.listed())
    std::printf("%s %.3f-%.3f s", &p == &tally.listed().front() ? ":" : ",", p.start_s, p.end_s);
  if (tally.presses() > tally.listed().size())
    std::printf(", and %llu more", static_cast<unsigned long long>(tally.presses() - tally.listed().size()));
  std::printf("\n  gaps       %llu repaired\n", static_cast<unsigned long long>(trace.repairs_made));
  for (const std::string& repair : trace.repairs) std::printf("    %s\n", repair.c_str());
  if (trace.repairs_made > trace.repairs.size())
    std::printf("    and %llu more\n", static_cast<unsigned long long>(trace.repairs_made - trace.repairs.size()));
  return 0;
}

int trace_synth_command(const SynthOptions& options) {
  SynthSpec spec = options.spec;
  if (!options.strokes.empty()) {
    spec.strokes.clear();
    for (const std::string& stroke : options.strokes) spec.strokes.push_back(parse_stroke(stroke));
  }
  const std::string text = synthesize_trace(spec);
  check_out(options.out, options.force);
  const Trace trace = read_back(text, options.out);
  write_whole(options.out, text);
  const std::size_t strokes = spec.strokes.size();
  std::printf("wrote %s: %zu samples over %.3f s at %g Hz, %zu stroke%s, seed %llu\n", options.out.c_str(),
              trace.samples.size(), trace.samples.back().t_s - trace.samples.front().t_s, trace.rate_hz, strokes,
              strokes == 1 ? "" : "s", static_cast<unsigned long long>(spec.seed));
  return 0;
}

}  // namespace bleedsim::cli
