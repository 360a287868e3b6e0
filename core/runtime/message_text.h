#pragma once
// Small text helpers for messages about bad input, shared by the scenario and trace readers.
#include <cstddef>
#include <string>

namespace bleedsim {

// The shortest text that reads back as the same double, so "must be at most 16 (got 16.0000001)"
// never prints as "(got 16)".
std::string format_number(double value);

// Levenshtein distance: how many single-character edits turn a into b (for "did you mean").
std::size_t edit_distance(const std::string& a, const std::string& b);

}  // namespace bleedsim
