#pragma once
// The scenario parser's test text: a valid scenario to break line by line, and the checks that a
// refusal names the file, the line and the key (shared by scenario_test.cpp and
// scenario_effects_test.cpp).
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "core/runtime/input_error.h"
#include "core/io/scenario.h"

namespace bleedsim::test {

// A made-up path: it appears in every message, and its stem names a scene that has no name key.
inline const std::string kPath = "scenarios/x.toml";

// A valid scenario, one key per line, so that a test can break line N and expect N in the message.
inline const std::string kBase =
    "[scene]\n"             //  1
    "width_px = 64\n"       //  2
    "height_px = 48\n"      //  3
    "width_mm = 16.0\n"     //  4
    "height_mm = 12.0\n"    //  5
    "duration_s = 0.5\n"    //  6
    "seed = 3\n"            //  7
    "[spread]\n"            //  8
    "radius_mm = 4.0\n"     //  9
    "[[cut]]\n"             // 10
    "x_mm = 8.0\n"          // 11
    "y_mm = 6.0\n"          // 12
    "[[cut]]\n"             // 13
    "x_mm = 2.0\n"          // 14
    "y_mm = 3.0\n"          // 15
    "radius_mm = 2.0\n"     // 16
    "[output]\n"            // 17
    "png_every = 0\n";      // 18
// The line that text appended to kBase starts on; it lands in the [output] table.
constexpr int kEnd = 19;

// A valid scene with an empty [particles] table last, so that text appended to it lands in
// [particles] (kParticlesEnd is the line it starts on).
inline const std::string kParticleBase =
    "[scene]\n"              //  1
    "width_px = 64\n"        //  2
    "height_px = 48\n"       //  3
    "width_mm = 16.0\n"      //  4
    "height_mm = 12.0\n"     //  5
    "duration_s = 0.5\n"     //  6
    "frame_rate_hz = 30\n"   //  7
    "[[cut]]\n"              //  8
    "x_mm = 8.0\n"           //  9
    "y_mm = 6.0\n"           // 10
    "[particles]\n";         // 11
constexpr int kParticlesEnd = 12;

inline std::string particles_with(const std::string& lines) { return kParticleBase + lines; }

inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

inline std::string joined(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& line : lines) text += line + "\n";
  return text;
}

// `text` with its line `line` (from 1) replaced by `by`.
inline std::string with_line(const std::string& text, int line, const std::string& by) {
  std::vector<std::string> lines = lines_of(text);
  lines.at(std::size_t(line - 1)) = by;
  return joined(lines);
}

// `text` with lines first..last turned into comments, so the lines after keep their numbers.
inline std::string without_lines(const std::string& text, int first, int last) {
  std::string result = text;
  for (int line = first; line <= last; ++line) result = with_line(result, line, "# (removed)");
  return result;
}

inline std::string line_part(int line) { return kPath + ":" + std::to_string(line) + ":"; }

// Parses `text` as kPath and checks it is refused at `line` (0: the file as a whole) and `key`
// with a message containing `gist`. An AssertionResult, so a failure points at the test's line.
inline ::testing::AssertionResult refused_at(const std::string& text, int line, const std::string& key,
                                      const std::string& gist) {
  try {
    parse_scenario(text, kPath);
  } catch (const InputError& e) {
    const std::string what = e.what();
    const std::string place = line > 0 ? line_part(line) : kPath + ": ";
    // "file:line:column: key: message", so the place starts the text and the key ends with ": ".
    const bool ok = what.rfind(place, 0) == 0 && e.where().line == line &&
                    e.key() == key && (key.empty() || what.find(" " + key + ": ") != std::string::npos) &&
                    what.find(gist) != std::string::npos;
    if (ok) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure()
           << "expected '" << place << "' at the start, key '" << key << "' and '" << gist
           << "'; got key '" << e.key() << "' and: " << what;
  }
  return ::testing::AssertionFailure() << "parsed without an error";
}

// The column a refusal of `text` points at; 0 when it is not refused.
inline int refused_column(const std::string& text) {
  try {
    parse_scenario(text, kPath);
  } catch (const InputError& e) {
    return e.where().column;
  }
  return 0;
}

}  // namespace bleedsim::test
