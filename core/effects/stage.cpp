#include "core/effects/stage.h"

namespace bleedsim {

Field image_field(const Scene& scene, const char* name, ElementType type, int channels, const char* unit,
                  const char* description) {
  Field field;
  field.name = name;
  field.type = type;
  field.channels = channels;
  field.width = scene.domain.width_px;
  field.height = scene.domain.height_px;
  field.unit = unit;
  field.description = description;
  return field;
}

Buffer Stage::allocate(Backend& backend, std::size_t bytes) {
  Buffer buffer = backend.allocate(bytes);
  bytes_ += bytes;
  return buffer;
}

Field& Stage::add_field(State& state, Backend& backend, Field field) {
  field.data = allocate(backend, field.bytes());
  state.fields.push_back(std::move(field));
  return state.fields.back();
}

}  // namespace bleedsim
