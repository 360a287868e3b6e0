#include "core/io/trace_csv.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <istream>
#include <map>
#include <optional>
#include <sstream>
#include <utility>
#include <vector>

#include "core/runtime/count.h"
#include "core/runtime/message_text.h"

namespace bleedsim {
namespace {

const char* const kColumns[] = {"t_s", "x_m", "y_m", "z_m", "buttons", "fx_N", "fy_N", "fz_N"};
const std::string kHeader = "t_s,x_m,y_m,z_m,buttons";
const std::string kForceHeader = "t_s,x_m,y_m,z_m,buttons,fx_N,fy_N,fz_N";
const char* const kRequired[] = {"device", "frame", "rate_hz"};

// A trace's metadata keys are few; a file with more is not a trace.
constexpr std::size_t kMaxMetadataKeys = 1000;

// A number for a human: four significant digits (rates, durations).
std::string rounded(double value) { return format_significant(value, 4); }

bool is_space(char c) { return c == ' ' || c == '\t'; }

// A field of a line: its text without surrounding blanks and its 1-based column.
struct Field {
  std::string text;
  int column;
};

Field trimmed(const std::string& line, std::size_t begin, std::size_t end) {
  while (begin < end && is_space(line[begin])) ++begin;
  while (end > begin && is_space(line[end - 1])) --end;
  return {line.substr(begin, end - begin), int(begin) + 1};
}

std::vector<Field> split_fields(const std::string& line) {
  std::vector<Field> fields;
  std::size_t begin = 0;
  for (;;) {
    const std::size_t comma = line.find(',', begin);
    const std::size_t end = comma == std::string::npos ? line.size() : comma;
    fields.push_back(trimmed(line, begin, end));
    if (comma == std::string::npos) break;
    begin = comma + 1;
  }
  return fields;
}

std::string lower(std::string text) {
  for (char& c : text) c = char(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

enum class Parsed { ok, not_a_number, not_finite };

// A plain decimal or exponent number ("0.0125", "-1.5e-3"), the whole text consumed. NaN and
// infinities (spelled out, or a value too large for a double) are told apart for the message.
Parsed parse_number(const std::string& text, double& value) {
  const std::string l = lower(text);
  const std::string body = !l.empty() && (l[0] == '+' || l[0] == '-') ? l.substr(1) : l;
  if (body == "nan" || body == "inf" || body == "infinity") {
    value = body == "nan" ? std::nan("") : (l[0] == '-' ? -HUGE_VAL : HUGE_VAL);
    return Parsed::not_finite;
  }
  if (text.empty() || text.find_first_not_of("0123456789+-.eE") != std::string::npos) return Parsed::not_a_number;
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size()) return Parsed::not_a_number;
  return std::isfinite(value) ? Parsed::ok : Parsed::not_finite;
}

// What a header column should have been, when it looks like the right quantity in other units.
std::string unit_hint(const std::string& got, const std::string& expected) {
  const auto stem = [](const std::string& name) { return lower(name.substr(0, name.find('_'))); };
  if (got == expected || stem(got) != stem(expected) || expected == "buttons") return "";
  if (expected == "t_s") return "time is in seconds (t_s)";
  if (expected[0] == 'f') return "forces are in newtons (" + expected + ")";
  return "positions are in metres (" + expected + ")";
}

class Parser {
 public:
  Parser(std::string path, const TraceOptions& options) : options_(options) { trace_.path = std::move(path); }

  [[noreturn]] void fail(int line, int column, const std::string& key, const std::string& message) const {
    throw InputError(SourcePlace{trace_.path, line, column}, key, message);
  }

  // Reads the lines of `in` one at a time, handing each sample to `take` until it wants no more:
  // only a line and the rate's window are held, never the whole text.
  Trace run(std::istream& in, const TakeSample& take) {
    std::string line;
    int number = 0;
    bool any_text = false;
    // The metadata block and the header.
    while (next_line(in, line, number)) {
      if (blank(line)) continue;
      any_text = true;
      if (line[line.find_first_not_of(" \t")] == '#') {
        read_metadata(line, number);
        continue;
      }
      header_line_ = number;
      break;
    }
    if (!any_text)
      fail(0, 0, "", "the file is empty (expected the metadata block, the header " + kHeader + " and samples)");
    if (header_line_ == 0)
      fail(0, 0, "header", "no header line: expected " + kHeader + " (or " + kForceHeader + ") after the metadata");
    read_header(line);
    check_metadata();

    // The samples, until `take` wants no more.
    bool wanted = true;
    while (wanted && next_line(in, line, number)) {
      if (blank(line) || line[line.find_first_not_of(" \t")] == '#') continue;
      wanted = accept(read_sample(line, number), number, take);
    }
    if (samples_read_ == 0) fail(header_line_, 0, "samples", "no samples after the header");
    check_rate();
    return std::move(trace_);
  }

 private:
  static bool blank(const std::string& line) {
    return std::all_of(line.begin(), line.end(), [](char c) { return is_space(c); });
  }

  // The next line of `in` without its end (LF or CR LF) as `line`, numbered from 1, refused past
  // kTraceMaxLineBytes. A UTF-8 byte-order mark before the first line is skipped (editors write
  // one); a UTF-16 one, or a carriage return that ends a line alone (old Mac line ends), is refused
  // at its place.
  bool next_line(std::istream& in, std::string& line, int& number) {
    in.getline(buffer_.data(), std::streamsize(buffer_.size()));
    const std::size_t got = std::size_t(in.gcount());
    if (in.fail() && got == 0) return false;  // the end of the text
    if (in.fail() && !in.eof())
      fail(number + 1, int(got), "", "the line is longer than " + std::to_string(kTraceMaxLineBytes) +
                                         " characters: a trace's lines are its metadata, its header and its samples");
    line.assign(buffer_.data(), in.eof() ? got : got - 1);  // without the LF that ended it
    ++number;
    if (number == 1) {
      if (line.compare(0, 3, "\xEF\xBB\xBF") == 0) line.erase(0, 3);
      else if (line.compare(0, 2, "\xFF\xFE") == 0 || line.compare(0, 2, "\xFE\xFF") == 0)
        fail(1, 1, "", "the file starts with a UTF-16 byte-order mark: a trace is UTF-8 (or ASCII) text; save it "
                       "as UTF-8");
    }
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::size_t cr = line.find('\r');
    if (cr != std::string::npos)
      fail(number, int(cr) + 1, "", "a carriage return (CR) alone ends a line here: lines must end in LF or CR LF "
                                    "(old Mac line ends? convert them, e.g. with tr '\\r' '\\n')");
    return true;
  }
  void read_metadata(const std::string& line, int number) {
    // "# key: value"; a '#' line of any other shape is a comment.
    const std::size_t hash = line.find('#');
    const std::size_t colon = line.find(':', hash);
    if (colon == std::string::npos) return;
    const Field key = trimmed(line, hash + 1, colon);
    if (key.text.empty() || key.text.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_.-") !=
                                std::string::npos)
      return;
    const Field value = trimmed(line, colon + 1, line.size());
    const std::string name = "metadata." + key.text;
    if (const auto seen = meta_lines_.find(key.text); seen != meta_lines_.end())
      fail(number, key.column, name, "given twice (first on line " + std::to_string(seen->second.first) + ")");
    if (meta_lines_.size() == kMaxMetadataKeys)
      fail(number, key.column, name, "more than " + std::to_string(kMaxMetadataKeys) + " metadata keys");
    meta_lines_[key.text] = {number, value.column};
    trace_.metadata[key.text] = value.text;

    if (key.text == "frame" && value.text != "libnifalcon")
      fail(number, value.column, name,
           "must be libnifalcon (the device frame as libnifalcon reports it: metres, x right, y up, z towards "
           "the user) (got '" + value.text + "')");
    if (key.text == "rate_hz") {
      double rate = 0;
      const Parsed p = parse_number(value.text, rate);
      if (p == Parsed::not_a_number) fail(number, value.column, name, "expected a number, got '" + value.text + "'");
      if (p == Parsed::not_finite) fail(number, value.column, name, "must be a finite number (got " + value.text + ")");
      if (rate < kTraceMinRate_hz || rate > kTraceMaxRate_hz)
        fail(number, value.column, name,
             "must be between " + format_number(kTraceMinRate_hz) + " and " + format_number(kTraceMaxRate_hz) +
                 " (got " + format_number(rate) + "): a sample rate near the Falcon's 1 kHz");
      trace_.rate_hz = rate;
    }
    if (key.text == "device" && value.text.empty()) fail(number, value.column, name, "must not be empty");
  }

  void check_metadata() const {
    for (const char* required : kRequired) {
      if (meta_lines_.count(required)) continue;
      std::string message = std::string("missing (required): the metadata block before the header needs a line '# ") +
                            required + ": ...'";
      // A near miss among the other keys ("rate", "Frame") is probably a misspelling.
      const std::string* nearest = nullptr;
      std::size_t best = 4;
      for (const auto& entry : meta_lines_) {
        const std::string& key = entry.first;  // a structured binding cannot be captured in C++17 (clang refuses)
        if (std::any_of(std::begin(kRequired), std::end(kRequired), [&](const char* r) { return key == r; })) continue;
        if (const std::size_t d = edit_distance(lower(key), required); d < best) best = d, nearest = &key;
      }
      if (nearest)
        message += "; line " + std::to_string(meta_lines_.at(*nearest).first) + " has '" + *nearest +
                   "': did you mean '" + required + "'?";
      fail(header_line_, 0, std::string("metadata.") + required, message);
    }
  }

  void read_header(const std::string& line) {
    const std::vector<Field> columns = split_fields(line);
    std::string got;
    for (const Field& c : columns) got += (got.empty() ? "" : ",") + c.text;
    if (got == kHeader || got == kForceHeader) {
      trace_.has_force = got == kForceHeader;
      return;
    }
    const std::string expected = "expected the header " + kHeader + " or " + kForceHeader;
    for (std::size_t c = 0; c < columns.size() && c < std::size(kColumns); ++c) {
      const std::string hint = unit_hint(columns[c].text, kColumns[c]);
      if (!hint.empty())
        fail(header_line_, columns[c].column, "header",
             "column " + std::to_string(c + 1) + " is '" + columns[c].text + "': " + hint + "; " + expected +
                 " (got '" + got + "')");
    }
    int column = 1;
    for (std::size_t c = 0; c < columns.size(); ++c)
      if (c >= std::size(kColumns) || columns[c].text != kColumns[c]) {
        column = columns[c].column;
        break;
      }
    fail(header_line_, column, "header", expected + " (got '" + got + "')");
  }

  double number(const Field& field, int line, const char* key) const {
    double value = 0;
    switch (parse_number(field.text, value)) {
      case Parsed::ok: return value;
      case Parsed::not_finite:
        fail(line, field.column, key, "must be a finite number (got " + field.text + ")");
      case Parsed::not_a_number:
        fail(line, field.column, key,
             field.text.empty() ? std::string("expected a number, got an empty value")
                                : "expected a number, got '" + field.text + "'");
    }
    return value;
  }

  void within(double value, double low, double high, const Field& field, int line, const char* key) const {
    if (value >= low && value <= high) return;
    fail(line, field.column, key,
         format_number(value) + " m is outside the Falcon's workspace: must be between " + format_number(low) +
             " and " + format_number(high) + " m (" + format_number(low * 1000) + " to " +
             format_number(high * 1000) + " mm)");
  }

  TraceSample read_sample(const std::string& line, int number_) const {
    const std::vector<Field> f = split_fields(line);
    const std::size_t want = trace_.has_force ? 8 : 5;
    if (f.size() != want)
      fail(number_, 1, "columns",
           "expected " + std::to_string(want) + " values (" + (trace_.has_force ? kForceHeader : kHeader) + "), got " +
               std::to_string(f.size()));
    TraceSample s;
    s.t_s = number(f[0], number_, "t_s");
    if (samples_read_ > 0 && !(s.t_s > last_.t_s))
      fail(number_, f[0].column, "t_s",
           "time must be strictly increasing: " + format_number(s.t_s) + " s is not after " +
               format_number(last_.t_s) + " s on line " + std::to_string(last_line_));
    s.x_m = number(f[1], number_, "x_m");
    s.y_m = number(f[2], number_, "y_m");
    s.z_m = number(f[3], number_, "z_m");
    within(s.x_m, kFalconMinXY_m, kFalconMaxXY_m, f[1], number_, "x_m");
    within(s.y_m, kFalconMinXY_m, kFalconMaxXY_m, f[2], number_, "y_m");
    within(s.z_m, kFalconMinZ_m, kFalconMaxZ_m, f[3], number_, "z_m");

    const std::string& b = f[4].text;
    if (b.empty() || b.find_first_not_of("0123456789") != std::string::npos || b.size() > 2 || std::stoi(b) > 15) {
      double ignored;
      if (b.empty() || parse_number(b, ignored) == Parsed::not_a_number)
        fail(number_, f[4].column, "buttons",
             "expected an integer, got " + (b.empty() ? std::string("an empty value") : "'" + b + "'"));
      fail(number_, f[4].column, "buttons",
           "must be an integer between 0 and 15, the bitmask of the four buttons 0x1..0x8 (got " + b + ")");
    }
    s.buttons = std::uint8_t(std::stoi(b));

    if (trace_.has_force) {
      s.fx_N = number(f[5], number_, "fx_N");
      s.fy_N = number(f[6], number_, "fy_N");
      s.fz_N = number(f[7], number_, "fz_N");
      const double magnitude = std::sqrt(s.fx_N * s.fx_N + s.fy_N * s.fy_N + s.fz_N * s.fz_N);
      if (magnitude > kFalconMaxForce_N)
        fail(number_, f[5].column, "force",
             "the force (" + f[5].text + ", " + f[6].text + ", " + f[7].text + ") N has magnitude " +
                 rounded(magnitude) + " N, over the Falcon's " + format_number(kFalconMaxForce_N) + " N maximum");
    }
    return s;
  }

  // A sample read: the dropout before it repaired (or refused), then it is handed to `take`.
  // Whether more samples are wanted.
  bool accept(const TraceSample& s, int line, const TakeSample& take) {
    bool wanted = true;
    if (samples_read_++ > 0) {
      const double gap = s.t_s - last_.t_s;
      if (intervals_.size() < kTraceRateWindow) intervals_.push_back(gap);
      if (gap > 1.5 / trace_.rate_hz) wanted = bridge(s, gap, line, take);
    }
    if (intervals_.size() == kTraceRateWindow) check_rate();
    wanted = wanted && !refused_ && take(s);
    last_ = s;
    last_line_ = line;
    // A dropout refused before the rate is checked waits for it: a wrong rate_hz explains it better.
    return wanted || (refused_ && !rate_checked_);
  }

  // The median interval must match rate_hz; then a dropout refused before is.
  void check_rate() {
    if (rate_checked_) return;
    rate_checked_ = true;
    const double period = 1.0 / trace_.rate_hz;
    const auto rate_line = meta_lines_.at("rate_hz");
    if (!intervals_.empty()) {
      std::vector<double>& dt = intervals_;
      std::nth_element(dt.begin(), dt.begin() + dt.size() / 2, dt.end());
      double median = dt[dt.size() / 2];
      if (dt.size() % 2 == 0) median = (median + *std::max_element(dt.begin(), dt.begin() + dt.size() / 2)) / 2;
      trace_.median_interval_s = median;
      if (std::abs(median - period) > 0.1 * period)
        fail(rate_line.first, rate_line.second, "metadata.rate_hz",
             "the samples are " + rounded(1.0 / median) + " Hz apart (median interval " + rounded(median * 1000) +
                 " ms), not the " + format_number(trace_.rate_hz) + " Hz the header states");
    }
    intervals_ = {};
    if (refused_) throw *refused_;
  }

  // The samples a dropout from the last sample to `b` lacks, at the nominal rate, interpolated and
  // handed to `take` in turn; or, when no repair may fill it, its refusal. Whether more are wanted.
  bool bridge(const TraceSample& b, double gap, int line, const TakeSample& take) {
    const TraceSample a = last_;
    const double period = 1.0 / trace_.rate_hz;
    const std::string what = "a " + rounded(gap * 1000) + " ms dropout after t = " + format_fixed(a.t_s, 4) + " s";
    if (!(options_.max_repair_gap_s > 0 && gap <= options_.max_repair_gap_s)) {
      const InputError refusal(
          SourcePlace{trace_.path, line, 1}, "t_s",
          what + " (between line " + std::to_string(last_line_) + " and line " + std::to_string(line) +
              "): the samples must be at most 1.5 intervals (" + rounded(1.5 * period * 1000) + " ms) apart at " +
              format_number(trace_.rate_hz) + " Hz" +
              (options_.max_repair_gap_s > 0 ? "; repairs are allowed up to " + rounded(options_.max_repair_gap_s * 1000) + " ms"
                                             : std::string()));
      if (rate_checked_) throw refusal;
      if (!refused_) refused_ = refusal;
      return true;
    }
    const long missing = std::max(1L, std::lround(gap / period)) - 1;
    long filled = 0;
    bool wanted = true;
    for (long m = 1; m <= missing && wanted; ++m) {
      const double t = a.t_s + double(m) * period;
      if (!(t < b.t_s)) break;
      const double u = (t - a.t_s) / gap;
      TraceSample f;
      f.t_s = t;
      f.x_m = a.x_m + u * (b.x_m - a.x_m);
      f.y_m = a.y_m + u * (b.y_m - a.y_m);
      f.z_m = a.z_m + u * (b.z_m - a.z_m);
      f.buttons = a.buttons;
      f.fx_N = a.fx_N + u * (b.fx_N - a.fx_N);
      f.fy_N = a.fy_N + u * (b.fy_N - a.fy_N);
      f.fz_N = a.fz_N + u * (b.fz_N - a.fz_N);
      wanted = refused_ || take(f);
      ++filled;
    }
    ++trace_.repairs_made;
    if (trace_.repairs.size() < kTraceRepairsDescribed)
      trace_.repairs.push_back(trace_.path + ":" + std::to_string(last_line_) + ": " + what + " filled with " +
                               std::to_string(filled) + " interpolated sample" + (filled == 1 ? "" : "s"));
    return wanted;
  }

  TraceOptions options_;
  Trace trace_;
  std::map<std::string, std::pair<int, int>> meta_lines_;  // key -> (line, value column)
  std::array<char, kTraceMaxLineBytes + 1> buffer_{};      // a line and getline's NUL
  int header_line_ = 0;
  std::uint64_t samples_read_ = 0;  // as written, repairs not counted
  TraceSample last_;                // the last sample read, and its line
  int last_line_ = 0;
  std::vector<double> intervals_;         // the first kTraceRateWindow, for the rate's median
  bool rate_checked_ = false;
  std::optional<InputError> refused_;     // the first dropout refused while the rate was unchecked
};

// Keeps the samples up to the first past options.keep_s, in a store whose growth is counted, the
// new store beside the old, before it is made.
Trace keep_samples(std::istream& in, const InputFile& file, const TraceOptions& options) {
  std::vector<TraceSample> kept;
  const auto take = [&](const TraceSample& s) {
    if (kept.size() == kept.capacity()) {
      const std::size_t grown = std::max<std::size_t>(1024, 2 * kept.capacity());
      const Count need = (Count(kept.capacity()) + grown) * sizeof(TraceSample);
      const std::size_t room = options.memory_room.value_or(available_host_memory());
      if (need > Count(room))
        throw unreadable(file, "keeping its samples up to t = " + format_fixed(s.t_s, 4) + " s, " +
                                   std::to_string(kept.size() + 1) + " of them, needs " + human_bytes(need.as_double()) +
                                   " of host memory, but only " + human_bytes(double(room)) + " is available");
      kept.reserve(grown);
    }
    kept.push_back(s);
    return !(s.t_s - kept.front().t_s > options.keep_s);
  };
  Trace trace = Parser(file.path, options).run(in, take);
  trace.samples = std::move(kept);
  return trace;
}

}  // namespace

Trace read_trace(const InputFile& file, const TraceOptions& options, const TakeSample& take) {
  std::ifstream in = open_input(file);
  return Parser(file.path, options).run(in, take);
}

Trace load_trace(const InputFile& file, const TraceOptions& options) {
  std::ifstream in = open_input(file);
  return keep_samples(in, file, options);
}

Trace parse_trace(const std::string& text, const std::string& path, const TraceOptions& options) {
  std::istringstream in(text);
  return keep_samples(in, InputFile{path, "trace file"}, options);
}

MemoryPart trace_memory(const Trace& trace, const InputFile& file) {
  return {file.key, "the " + std::to_string(trace.samples.size()) + " samples kept of trace '" + file.path + "'",
          Count(trace.samples.capacity()) * sizeof(TraceSample)};
}

}  // namespace bleedsim
