#pragma once
// Incidence: compressed lists of ids (offsets + one flat array), as the element / B-spline incidence of a locally
// refined spline ("which B-splines live on which element" and back). One allocation for all lists instead of one
// per list, and a transposition that writes into the storage it is given.
#include <algorithm>
#include <functional>
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
  Incidence transposed(int num_targets) const;
};

// The lists list(0), ..., list(num_lists - 1) (spans of ids j) the other way round, into `out`: list target(j)
// of `out` holds every i whose list holds j, ascending (target(j) < num_targets). An empty list(i) leaves i out;
// target renumbers the ids on the way. A caller that knows how long the result's lists are gives their lengths
// as `sizes` (num_targets of them), which saves a pass over all ids to count them. `out`'s storage is reused: a
// refinement transposes its lists after every batch, and storage that is large enough is neither allocated nor
// zero-filled again.
template <class Lists, class Target = std::identity>
void transpose_into(Incidence& out, int num_targets, int num_lists, Lists list, Target target = {},
                    std::span<const int> sizes = {}) {
  const auto n = static_cast<std::size_t>(num_targets);
  auto& at = out.offsets;
  // Each length goes two places up, so that after the running sum at[t + 1] is where list t starts; writing list
  // t moves it to where the list ends, its final value as offset t + 1, so no separate write positions are needed.
  at.resize(n + 2);
  at[0] = at[1] = 0;
  if (sizes.empty()) {
    std::fill(at.begin() + 2, at.end(), 0);
    for (int i = 0; i < num_lists; ++i)
      for (int j : list(i)) ++at[static_cast<std::size_t>(target(j)) + 2];
  } else {
    std::copy(sizes.begin(), sizes.end(), at.begin() + 2);
  }
  for (std::size_t t = 2; t < n + 2; ++t) at[t] += at[t - 1];
  out.ids.resize(static_cast<std::size_t>(at[n + 1]));
  for (int i = 0; i < num_lists; ++i)
    for (int j : list(i)) out.ids[static_cast<std::size_t>(at[static_cast<std::size_t>(target(j)) + 1]++)] = i;
  at.pop_back();
}

inline Incidence Incidence::transposed(int num_targets) const {
  Incidence t;
  transpose_into(t, num_targets, size(), [this](int i) { return (*this)[i]; });
  return t;
}

}  // namespace trivar
