#pragma once
// Values of different types, at most one of each, found by their type: a scene's effects (each
// held as its parameters, Scene::effects) and what a scene's effects resolve to (Resolved). The
// scene names no effect: an effect's folder and its row in core/effects/effect_list.h are all that
// add one (docs/architecture.md, "Adding an effect"), and no floor below the effects includes them.
#include <algorithm>
#include <any>
#include <stdexcept>
#include <typeindex>
#include <typeinfo>
#include <utility>
#include <vector>

namespace bleedsim {

class TypeMap {
 public:
  // The P held, or null when there is none.
  template <class P>
  const P* find() const {
    const auto at = entry(typeid(P));
    return at == entries_.end() ? nullptr : std::any_cast<P>(&at->second);
  }
  template <class P>
  P* find() {
    return const_cast<P*>(std::as_const(*this).find<P>());
  }
  template <class P>
  bool has() const {
    return find<P>() != nullptr;
  }
  // Throws std::logic_error when there is no P: code that reads an effect's parameters runs only
  // for scenes that declare it.
  template <class P>
  const P& get() const {
    if (const P* params = find<P>()) return *params;
    throw std::logic_error(std::string("no value of type ") + typeid(P).name() + " is held");
  }
  template <class P>
  P& get() {
    return const_cast<P&>(std::as_const(*this).get<P>());
  }
  // Holds `value` as its type's, replacing any held.
  template <class P>
  P& set(P value) {
    drop<P>();
    entries_.emplace_back(std::type_index(typeid(P)), std::move(value));
    return *std::any_cast<P>(&entries_.back().second);
  }
  template <class P>
  void drop() {
    const auto at = entry(typeid(P));
    if (at != entries_.end()) entries_.erase(at);
  }

 private:
  using Entry = std::pair<std::type_index, std::any>;
  std::vector<Entry>::const_iterator entry(const std::type_info& type) const {
    return std::find_if(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.first == type; });
  }
  std::vector<Entry> entries_;
};

}  // namespace bleedsim
