#include "core/io/trace_synth.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "core/physics/counter_hash.h"
#include "core/runtime/input_error.h"
#include "core/runtime/message_text.h"
#include "core/io/trace_csv.h"

namespace bleedsim {
namespace {

// Long enough for any sensible session, short enough that the text stays tens of megabytes.
constexpr double kMaxDuration_s = 600;

// A point of the device frame, in millimetres.
struct Point {
  double x, y, z;
};

enum class Pace {
  eased,   // a hand starting and stopping: no jump in velocity at either end
  steady,  // the cut itself, at the speed asked for, so the tissue sees that speed throughout
};

// The tool going from `from` to `to` over samples [begin, end), with these grip buttons held (0: none).
struct Move {
  long begin, end;
  Point from, to;
  Pace pace;
  int buttons;
};

// Moves end on the sample nearest their end time, summed from the start, so rounding never
// accumulates over a long trace.
class Plan {
 public:
  Plan(Point start, double rate_hz) : at_(start), rate_hz_(rate_hz) {}

  void go(Point to, double duration_s, Pace pace, int buttons) {
    elapsed_s_ += duration_s;
    const long end = std::lround(elapsed_s_ * rate_hz_);
    moves_.push_back({moves_.empty() ? 0 : moves_.back().end, end, at_, to, pace, buttons});
    at_ = to;
  }
  void stay(double duration_s) { go(at_, duration_s, Pace::eased, false); }

  const std::vector<Move>& moves() const { return moves_; }

 private:
  Point at_;
  double rate_hz_;
  double elapsed_s_ = 0;
  std::vector<Move> moves_;
};

double stroke_length_mm(const StrokeSpec& s) { return std::hypot(s.to_x_mm - s.from_x_mm, s.to_y_mm - s.from_y_mm); }

// Rest above the first stroke; then, for each stroke, down onto the tissue, into it with its buttons
// pressed, along the cut, back up with the button released, and over to the next stroke's start
// while pausing above the tissue.
std::vector<Move> motion(const SynthSpec& spec) {
  const double surface = spec.surface_z_mm, cut = surface - spec.depth_mm, hover = surface + spec.hover_mm;
  const StrokeSpec& first = spec.strokes.front();
  Plan p({first.from_x_mm, first.from_y_mm, hover}, spec.rate_hz);
  p.stay(spec.pause_s);
  for (std::size_t k = 0; k < spec.strokes.size(); ++k) {
    const StrokeSpec& s = spec.strokes[k];
    p.go({s.from_x_mm, s.from_y_mm, surface}, spec.approach_s, Pace::eased, 0);
    p.go({s.from_x_mm, s.from_y_mm, cut}, spec.press_s, Pace::eased, s.buttons);
    p.go({s.to_x_mm, s.to_y_mm, cut}, stroke_length_mm(s) / spec.speed_mm_s, Pace::steady, s.buttons);
    p.go({s.to_x_mm, s.to_y_mm, hover}, spec.lift_s, Pace::eased, 0);
    if (k + 1 < spec.strokes.size()) {
      const StrokeSpec& next = spec.strokes[k + 1];
      p.go({next.from_x_mm, next.from_y_mm, hover}, spec.pause_s, Pace::eased, 0);
    } else {
      p.stay(spec.pause_s);
    }
  }
  return p.moves();
}

// Smoothstep: zero velocity at both ends.
double eased(double u) { return u * u * (3 - 2 * u); }

Point along(const Move& m, long sample) {
  const double u = double(sample - m.begin) / double(m.end - m.begin);
  const double w = m.pace == Pace::eased ? eased(u) : u;
  return {m.from.x + w * (m.to.x - m.from.x), m.from.y + w * (m.to.y - m.from.y),
          m.from.z + w * (m.to.z - m.from.z)};
}

// Physiological hand tremor: an 8–12 Hz oscillation of a tenth of a millimetre or so, made here of
// three sinusoids per axis whose frequencies and phases the seed draws. The weights sum to 1, so an
// axis never strays more than the amplitude from the planned path.
class Tremor {
 public:
  Tremor(std::uint64_t seed, double amplitude_mm) {
    for (std::uint64_t axis = 0; axis < 3; ++axis)
      for (std::uint64_t k = 0; k < kParts; ++k) {
        Part& part = parts_[axis][k];
        part.amplitude_mm = amplitude_mm * kWeights[k];
        part.frequency_hz = 10.0 + 2.0 * signed_unit(counter_hash(seed, axis, k, 0));
        part.phase = M_PI * signed_unit(counter_hash(seed, axis, k, 1));
      }
  }

  Point at(double t_s) const { return {on(0, t_s), on(1, t_s), on(2, t_s)}; }

 private:
  static constexpr std::size_t kParts = 3;
  static constexpr double kWeights[kParts] = {0.5, 0.3, 0.2};
  struct Part {
    double amplitude_mm, frequency_hz, phase;
  };

  double on(std::size_t axis, double t_s) const {
    double sum = 0;
    for (const Part& p : parts_[axis]) sum += p.amplitude_mm * std::sin(2 * M_PI * p.frequency_hz * t_s + p.phase);
    return sum;
  }

  Part parts_[3][kParts];
};

[[noreturn]] void refuse(const std::string& option, const std::string& message) {
  throw InputError(SourcePlace{}, option, message);
}

void require_positive(double value, const char* option, const char* unit) {
  if (!(value > 0) || !std::isfinite(value))
    refuse(option, std::string("must be a positive number of ") + unit + " (got " + format_number(value) + ")");
}

void check_rates_and_durations(const SynthSpec& spec) {
  if (!(spec.rate_hz >= kTraceMinRate_hz && spec.rate_hz <= kTraceMaxRate_hz))
    refuse("--rate-hz", "must be between " + format_number(kTraceMinRate_hz) + " and " +
                            format_number(kTraceMaxRate_hz) + " Hz (got " + format_number(spec.rate_hz) +
                            "): a sample rate near the Falcon's 1 kHz, as every trace has");
  require_positive(spec.speed_mm_s, "--speed-mm-s", "mm/s");
  require_positive(spec.approach_s, "--approach-s", "seconds");
  require_positive(spec.press_s, "--press-s", "seconds");
  require_positive(spec.lift_s, "--lift-s", "seconds");
  require_positive(spec.pause_s, "--pause-s", "seconds");
}

void check_heights(const SynthSpec& spec) {
  const double tremor_mm = spec.tremor_um / 1000;
  if (!(spec.tremor_um >= 0 && spec.tremor_um < 1000))
    refuse("--tremor-um", "must be at least 0 and under 1000 µm: a physiological tremor is sub-millimetre (got " +
                              format_number(spec.tremor_um) + ")");
  if (!(spec.depth_mm >= 0) || !std::isfinite(spec.depth_mm))
    refuse("--depth-mm", "must be 0 mm or more (got " + format_number(spec.depth_mm) + ")");
  require_positive(spec.hover_mm, "--hover-mm", "mm");
  if (spec.hover_mm <= tremor_mm)
    refuse("--hover-mm", "must be more than the " + format_number(tremor_mm) +
                             " mm tremor, so that the waiting tool stays clear of the tissue (got " +
                             format_number(spec.hover_mm) + ")");

  const std::string workspace_z = "the Falcon's workspace (z " + format_number(kFalconMinZ_m * 1000) + " to " +
                                  format_number(kFalconMaxZ_m * 1000) + " mm)";
  const double surface = spec.surface_z_mm;
  if (!(surface >= kFalconMinZ_m * 1000 && surface <= kFalconMaxZ_m * 1000))
    refuse("--surface-z-mm", "must be inside " + workspace_z + " (got " + format_number(surface) + ")");
  if (const double top = surface + spec.hover_mm + tremor_mm; top > kFalconMaxZ_m * 1000)
    refuse("--hover-mm", "hovering " + format_number(spec.hover_mm) + " mm above the surface at z = " +
                             format_number(surface) + " mm takes the tool, tremor included, to z = " +
                             format_number(top) + " mm, above " + workspace_z);
  if (const double bottom = surface - spec.depth_mm - tremor_mm; bottom < kFalconMinZ_m * 1000)
    refuse("--depth-mm", "cutting " + format_number(spec.depth_mm) + " mm below the surface at z = " +
                             format_number(surface) + " mm takes the tool, tremor included, to z = " +
                             format_number(bottom) + " mm, below " + workspace_z);
}

void check_strokes(const SynthSpec& spec) {
  if (spec.strokes.empty()) refuse("--stroke", "give at least one stroke");
  const double tremor_mm = spec.tremor_um / 1000;
  for (std::size_t k = 0; k < spec.strokes.size(); ++k) {
    const StrokeSpec& s = spec.strokes[k];
    const std::string which = "stroke " + std::to_string(k + 1);
    for (const double v : {s.from_x_mm, s.from_y_mm, s.to_x_mm, s.to_y_mm}) {
      if (!std::isfinite(v)) refuse("--stroke", which + ": every coordinate must be a finite number of mm");
      if (std::abs(v) + tremor_mm > kFalconMaxXY_m * 1000)
        refuse("--stroke", which + " reaches " + format_number(v) + " mm; with the " + format_number(tremor_mm) +
                               " mm tremor the tool must stay inside the Falcon's workspace (x and y " +
                               format_number(kFalconMinXY_m * 1000) + " to " + format_number(kFalconMaxXY_m * 1000) +
                               " mm)");
    }
    if (s.buttons < 1 || s.buttons > 15)
      refuse("--stroke", which + " holds buttons " + std::to_string(s.buttons) +
                             ": the grip buttons are a bitmask from 1 to 15");
    if (stroke_length_mm(s) == 0)
      refuse("--stroke", which + " starts and ends at (" + format_number(s.from_x_mm) + ", " +
                             format_number(s.from_y_mm) + ") mm: a stroke must go somewhere");
  }
}

void check_duration(const SynthSpec& spec) {
  double total_s = spec.pause_s;
  for (const StrokeSpec& s : spec.strokes)
    total_s += spec.approach_s + spec.press_s + stroke_length_mm(s) / spec.speed_mm_s + spec.lift_s + spec.pause_s;
  if (total_s > kMaxDuration_s)
    refuse("", "the trace would last " + format_number(std::round(total_s)) + " s, over the " +
                   format_number(kMaxDuration_s) + " s a synthetic trace may: give fewer --stroke, a faster "
                   "--speed-mm-s or shorter --pause-s, --approach-s, --press-s or --lift-s");
}

// How the file came to be, as a command that makes it again (numbers as they read back exactly).
std::string generator(const SynthSpec& spec) {
  std::string line = "bleedsim trace synth --seed " + std::to_string(spec.seed);
  for (const StrokeSpec& s : spec.strokes)
    line += " --stroke " + format_number(s.from_x_mm) + "," + format_number(s.from_y_mm) + "," +
            format_number(s.to_x_mm) + "," + format_number(s.to_y_mm) +
            (s.buttons == 1 ? "" : "," + std::to_string(s.buttons));
  const std::pair<const char*, double> options[] = {
      {"--surface-z-mm", spec.surface_z_mm}, {"--depth-mm", spec.depth_mm},   {"--hover-mm", spec.hover_mm},
      {"--speed-mm-s", spec.speed_mm_s},     {"--approach-s", spec.approach_s}, {"--press-s", spec.press_s},
      {"--lift-s", spec.lift_s},             {"--pause-s", spec.pause_s},     {"--tremor-um", spec.tremor_um},
      {"--rate-hz", spec.rate_hz}};
  for (const auto& [name, value] : options) line += std::string(" ") + name + " " + format_number(value);
  return line;
}

std::string metadata(const SynthSpec& spec) {
  return "# device: Novint Falcon (synthetic)\n"
         "# frame: libnifalcon\n"
         "# rate_hz: " + format_number(spec.rate_hz) + "\n"
         "# origin: synthetic\n"
         "# seed: " + std::to_string(spec.seed) + "\n"
         "# generator: " + generator(spec) + "\n"
         "t_s,x_m,y_m,z_m,buttons\n";
}

}  // namespace

std::string synthesize_trace(const SynthSpec& spec) {
  check_rates_and_durations(spec);
  check_heights(spec);
  check_strokes(spec);
  check_duration(spec);

  const std::vector<Move> moves = motion(spec);
  const Tremor tremor(spec.seed, spec.tremor_um / 1000);
  const long last = moves.back().end;
  std::string text = metadata(spec);
  text.reserve(text.size() + std::size_t(last + 1) * 40);
  std::size_t m = 0;
  for (long i = 0; i <= last; ++i) {
    while (m + 1 < moves.size() && i >= moves[m].end) ++m;
    const Move& move = moves[m];
    // The last sample is where the last move ends.
    const Point planned = i < move.end ? along(move, i) : move.to;
    const int buttons = i < move.end ? move.buttons : 0;
    const double t_s = double(i) / spec.rate_hz;
    const Point shake = tremor.at(t_s);
    char line[96];
    std::snprintf(line, sizeof line, "%.4f,%.6f,%.6f,%.6f,%d\n", t_s, (planned.x + shake.x) / 1000,
                  (planned.y + shake.y) / 1000, (planned.z + shake.z) / 1000, buttons);
    text += line;
  }
  return text;
}

}  // namespace bleedsim
