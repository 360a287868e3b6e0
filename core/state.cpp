#include "core/state.h"

namespace bleedsim {

std::size_t element_size(ElementType type) { return type == ElementType::u8 ? 1 : 4; }

Field* State::find(const std::string& name) {
  for (Field& field : fields)
    if (field.name == name) return &field;
  return nullptr;
}

const Field* State::find(const std::string& name) const {
  return const_cast<State*>(this)->find(name);
}

}  // namespace bleedsim
