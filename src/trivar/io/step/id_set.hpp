#pragma once
// A set of instance ids stored as disjoint intervals. Files number their instances mostly in increasing,
// dense order, so this stays a handful of intervals while recording every id defined in a file of
// hundreds of MB, including the instances a reader's filter dropped.
#include <cstdint>
#include <map>

namespace trivar::io::step {

class IdSet {
public:
  // Adds id; returns false when it was already present.
  bool insert(std::uint64_t id);
  bool contains(std::uint64_t id) const;
  std::size_t intervals() const { return spans_.size(); }

private:
  std::map<std::uint64_t, std::uint64_t> spans_;  // first -> last, inclusive, disjoint and non-adjacent
};

}  // namespace trivar::io::step
