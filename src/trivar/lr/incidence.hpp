#pragma once
// Incidence: compressed lists of ids (offsets + one flat array), as the element / B-spline incidence of a locally
// refined spline ("which B-splines live on which element" and back). One allocation for all lists instead of one
// per list, and a transposition that writes into presized storage.
#include <span>
#include <vector>

namespace trivar {

// List i is ids[offsets[i] .. offsets[i+1]).
struct Incidence {
  std::vector<int> offsets{0};
  std::vector<int> ids;

  int size() const { return static_cast<int>(offsets.size()) - 1; }
  std::span<const int> operator[](int i) const {
    return {ids.data() + offsets[static_cast<std::size_t>(i)],
            static_cast<std::size_t>(offsets[static_cast<std::size_t>(i) + 1] - offsets[static_cast<std::size_t>(i)])};
  }
  // The lists the other way round: list j of the result holds every i whose list holds j (j < num_targets),
  // ascending.
  Incidence transposed(int num_targets) const {
    Incidence t;
    t.offsets.assign(static_cast<std::size_t>(num_targets) + 1, 0);
    for (int j : ids) ++t.offsets[static_cast<std::size_t>(j) + 1];
    for (std::size_t j = 0; j < static_cast<std::size_t>(num_targets); ++j) t.offsets[j + 1] += t.offsets[j];
    t.ids.resize(ids.size());
    std::vector<int> fill(t.offsets.begin(), t.offsets.end() - 1);
    for (int i = 0; i < size(); ++i)
      for (int j : (*this)[i]) t.ids[static_cast<std::size_t>(fill[static_cast<std::size_t>(j)]++)] = i;
    return t;
  }
};

}  // namespace trivar
