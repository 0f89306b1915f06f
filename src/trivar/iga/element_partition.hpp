#pragma once
// A share of a patch's elements for one of several processes: the element layers along the patch's last
// parametric direction cut into `parts` contiguous slabs of nearly equal size. Assembly, loads and error norms
// restricted to one part visit only its elements, so the parts' results sum to the whole (distributed
// assembly, iga_petsc/). The default is the whole patch.
#include <utility>

namespace trivar {

struct ElementPartition {
  int part = 0, parts = 1;

  bool whole() const { return parts == 1; }
  // The layers [first, second) of this part out of `layers`.
  std::pair<int, int> layers(int total) const {
    const long t = total;
    return {static_cast<int>(t * part / parts), static_cast<int>(t * (part + 1) / parts)};
  }
};

}  // namespace trivar
