#include "core/stage.h"

namespace bleedsim {

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
