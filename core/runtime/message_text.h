#pragma once
// Small text helpers for messages about bad input, shared by the scenario and trace readers.
#include <cstddef>
#include <string>

namespace bleedsim {

// The shortest text that reads back as the same double, so "must be at most 16 (got 16.0000001)"
// never prints as "(got 16)".
std::string format_number(double value);
// `digits` significant digits ("%.*g"): for people reading rates, durations and table cells.
std::string format_significant(double value, int digits);
// `decimals` digits after the point ("%.*f").
std::string format_fixed(double value, int decimals);

// Levenshtein distance: how many single-character edits turn a into b (for "did you mean").
std::size_t edit_distance(const std::string& a, const std::string& b);

}  // namespace bleedsim
