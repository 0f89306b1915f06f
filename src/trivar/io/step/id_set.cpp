#include "trivar/io/step/id_set.hpp"

#include <iterator>

namespace trivar::io::step {

bool IdSet::insert(std::uint64_t id) {
  if (!spans_.empty()) {
    auto last = std::prev(spans_.end());
    if (id == last->second + 1) {  // the common case: the next id in file order
      last->second = id;
      return true;
    }
    if (id > last->second + 1) {
      spans_.emplace_hint(spans_.end(), id, id);
      return true;
    }
  }
  auto next = spans_.upper_bound(id);
  if (next != spans_.begin()) {
    auto prev = std::prev(next);
    if (id <= prev->second) return false;
    if (id == prev->second + 1) {
      prev->second = id;
      if (next != spans_.end() && next->first == id + 1) {
        prev->second = next->second;
        spans_.erase(next);
      }
      return true;
    }
  }
  if (next != spans_.end() && next->first == id + 1) {
    const std::uint64_t last = next->second;
    spans_.erase(next);
    spans_.emplace(id, last);
  } else {
    spans_.emplace(id, id);
  }
  return true;
}

bool IdSet::contains(std::uint64_t id) const {
  auto next = spans_.upper_bound(id);
  return next != spans_.begin() && id <= std::prev(next)->second;
}

}  // namespace trivar::io::step
