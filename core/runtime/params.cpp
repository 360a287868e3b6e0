#include "core/runtime/params.h"

#include <cmath>

#include "core/runtime/message_text.h"

namespace bleedsim {
namespace {

// Integers print as integers (a seed's bound is 2⁶³ − 1, which a double holds only as 2⁶³).
std::string bound_text(double v, ParamType type) {
  if (type != ParamType::integer) return format_number(v);
  if (v >= 9223372036854775807.0) return "9223372036854775807";
  return std::to_string(static_cast<long long>(v));
}

}  // namespace

const char* to_string(ParamType type) {
  switch (type) {
    case ParamType::integer: return "integer";
    case ParamType::number: return "number";
    case ParamType::vector: return "[x, y] numbers";
    case ParamType::vector3: return "[x, y, z] numbers";
    case ParamType::text: return "string";
    case ParamType::flag: return "boolean";
    case ParamType::names: return "array of strings";
  }
  return "";
}

bool Range::contains(double v) const {
  if (!(above ? v > low : v >= low) || !(v <= high)) return false;
  if (only.empty()) return true;
  for (const double allowed : only)
    if (v == allowed) return true;
  return false;
}

std::string Range::describe(ParamType type) const {
  if (!only.empty()) {
    std::string text;
    for (std::size_t i = 0; i < only.size(); ++i)
      text += (i == 0 ? "" : i + 1 == only.size() ? " or " : ", ") + bound_text(only[i], type);
    return text;
  }
  if (above) return "greater than " + bound_text(low, type) + " and at most " + bound_text(high, type);
  return "between " + bound_text(low, type) + " and " + bound_text(high, type);
}

ParamProblem range_problem(const std::string& key, ParamType type, const Range& range, double value) {
  if (!std::isfinite(value)) return {key, "must be a finite number (got " + format_number(value) + ")"};
  if (type == ParamType::integer && value != std::floor(value))
    return {key, "must be a whole number (got " + format_number(value) + ")"};
  if (!range.contains(value))
    return {key, "must be " + range.describe(type) + " (got " + format_number(value) + ")"};
  return {};
}

std::string ParamView::default_text() const {
  if (required) return "required";
  if (!default_note.empty()) return default_note;
  struct Text {
    std::string operator()(std::monostate) const { return "none"; }
    std::string operator()(double v) const { return format_number(v); }
    std::string operator()(const std::vector<double>& v) const {
      std::string out;
      for (double c : v) out += (out.empty() ? "[" : ", ") + format_number(c);
      return out + "]";
    }
    std::string operator()(const std::string& v) const { return v.empty() ? "none" : "\"" + v + "\""; }
    std::string operator()(bool v) const { return v ? "true" : "false"; }
    std::string operator()(const std::vector<std::string>& v) const { return v.empty() ? "[]" : "[…]"; }
  };
  return std::visit(Text{}, default_value);
}

std::string ParamView::allowed_text() const {
  if (!allowed_note.empty()) return allowed_note;
  switch (type) {
    case ParamType::integer:
    case ParamType::number: return range.describe(type);
    case ParamType::vector:
    case ParamType::vector3: return "each " + range.describe(type);
    case ParamType::flag: return "true or false";
    default: return "";
  }
}

}  // namespace bleedsim
