#include "core/runtime/input_error.h"

namespace bleedsim {
namespace {

std::string describe(const SourcePlace& where, const std::string& key, const std::string& message) {
  std::string text = where.file.empty() ? std::string() : where.file + ":";
  if (where.line > 0) {
    text += std::to_string(where.line) + ":";
    if (where.column > 0) text += std::to_string(where.column) + ":";
  }
  if (!text.empty()) text += " ";
  if (!key.empty()) text += key + ": ";
  return text + message;
}

}  // namespace

InputError::InputError(const SourcePlace& where, const std::string& key, const std::string& message)
    : std::runtime_error(describe(where, key, message)), where_(where), key_(key) {}

}  // namespace bleedsim
