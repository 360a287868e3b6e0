#include "core/scene/state.h"

#include <stdexcept>

namespace bleedsim {

std::size_t element_size(ElementType type) {
  switch (type) {
    case ElementType::u8: return 1;
    case ElementType::u64: return 8;
    default: return 4;
  }
}

Field* State::find(const std::string& name) {
  for (Field& field : fields)
    if (field.name == name) return &field;
  return nullptr;
}

const Field* State::find(const std::string& name) const {
  return const_cast<State*>(this)->find(name);
}

const Field& State::require(const std::string& name) const {
  const Field* field = find(name);
  if (!field) throw std::logic_error("no stage has added the field " + name);
  return *field;
}

}  // namespace bleedsim
