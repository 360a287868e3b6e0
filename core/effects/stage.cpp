#include "core/effects/stage.h"

#include <algorithm>
#include <stdexcept>

namespace bleedsim {

Buffer Stage::allocate(Backend& backend, std::size_t bytes) {
  Buffer buffer = backend.allocate(bytes);
  bytes_ += bytes;
  return buffer;
}

Field& Stage::add_field(const Scene& scene, State& state, Backend& backend, const std::string& name, int elements) {
  const FieldLayout* layout = kind_.written(name);
  if (!layout) throw std::logic_error("the " + name_ + " stage adds " + name + ", which its kind does not declare");
  Field field;
  static_cast<FieldLayout&>(field) = *layout;
  field.width = layout->image ? scene.domain.width_px : elements;
  field.height = layout->image ? scene.domain.height_px : 1;
  field.data = allocate(backend, field.bytes());
  state.fields.push_back(std::move(field));
  return state.fields.back();
}

const Field& Stage::input(const Scene& scene, const State& state, const std::string& name) const {
  const std::vector<std::string> reads = kind_.reads(scene);
  if (std::find(reads.begin(), reads.end(), name) == reads.end())
    throw std::logic_error("the " + name_ + " stage reads " + name + ", which its kind does not declare");
  return state.require(name);
}

}  // namespace bleedsim
