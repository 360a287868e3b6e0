#include "core/effects/stage_kinds.h"

namespace bleedsim {

FieldLayout image_field(const char* name, ElementType type, int channels, const char* unit, const char* description) {
  FieldLayout field;
  field.name = name;
  field.type = type;
  field.channels = channels;
  field.unit = unit;
  field.description = description;
  return field;
}

FieldLayout element_field(const char* name, ElementType type, int channels, bool on_request, const char* unit,
                          const char* description) {
  FieldLayout field = image_field(name, type, channels, unit, description);
  field.image = false;
  field.on_request = on_request;
  return field;
}

FieldLayout on_request(FieldLayout field) {
  field.on_request = true;
  return field;
}

std::vector<std::string> no_fields(const Scene&) { return {}; }

const FieldLayout* StageKind::written(const std::string& field) const {
  for (const FieldLayout& layout : writes)
    if (layout.name == field) return &layout;
  return nullptr;
}

const StageKind* stage_writing(const std::string& field) {
  for (const StageKind& kind : stage_kinds())
    if (kind.written(field)) return &kind;
  return nullptr;
}

}  // namespace bleedsim
