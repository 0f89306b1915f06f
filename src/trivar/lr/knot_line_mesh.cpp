#include "trivar/lr/knot_line_mesh.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <utility>

namespace trivar {

namespace {

// Appends to `out` the union of the rectangles of one plane as maximal pieces: per level m, the cells (of the
// grid of all rectangle bounds) covered with multiplicity >= m, merged into runs along the first direction
// across the plane and then runs of equal extent along the second; each piece gets multiplicity m.
template <int D>
void merge_plane(int dir, double value, const std::vector<MeshRectangle<D>>& rects,
                 std::vector<MeshRectangle<D>>& out) {
  std::array<int, 2> across{0, 0};
  int na = 0;
  for (int j = 0; j < D; ++j)
    if (j != dir) across[static_cast<std::size_t>(na++)] = j;
  std::array<std::vector<double>, 2> cuts;
  for (int c = 0; c < na; ++c) {
    auto& v = cuts[static_cast<std::size_t>(c)];
    for (const auto& r : rects) {
      v.push_back(r.extent.lo[across[static_cast<std::size_t>(c)]]);
      v.push_back(r.extent.hi[across[static_cast<std::size_t>(c)]]);
    }
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
  }
  const std::size_t n0 = cuts[0].size() - 1, n1 = na == 2 ? cuts[1].size() - 1 : 1;
  std::vector<int> mult(n0 * n1, 0);
  int top = 0;
  for (const auto& r : rects) {
    const auto range = [&](int c) {
      const auto& v = cuts[static_cast<std::size_t>(c)];
      const int j = across[static_cast<std::size_t>(c)];
      return std::pair<std::size_t, std::size_t>(
          static_cast<std::size_t>(std::lower_bound(v.begin(), v.end(), r.extent.lo[j]) - v.begin()),
          static_cast<std::size_t>(std::lower_bound(v.begin(), v.end(), r.extent.hi[j]) - v.begin()));
    };
    const auto [a0, a1] = range(0);
    const auto [b0, b1] = na == 2 ? range(1) : std::pair<std::size_t, std::size_t>(0, 1);
    for (std::size_t j = b0; j < b1; ++j)
      for (std::size_t i = a0; i < a1; ++i) mult[j * n0 + i] = std::max(mult[j * n0 + i], r.multiplicity);
    top = std::max(top, r.multiplicity);
  }
  for (int m = 1; m <= top; ++m) {
    // Open pieces: run [i0, i1) along the first direction -> first row j0.
    std::map<std::pair<std::size_t, std::size_t>, std::size_t> open;
    const auto emit = [&](std::size_t i0, std::size_t i1, std::size_t j0, std::size_t j1) {
      Param<D> lo{}, hi{};
      lo[across[0]] = cuts[0][i0];
      hi[across[0]] = cuts[0][i1];
      if (na == 2) {
        lo[across[1]] = cuts[1][j0];
        hi[across[1]] = cuts[1][j1];
      }
      out.push_back(MeshRectangle<D>::make(dir, value, lo, hi, m));
    };
    for (std::size_t j = 0; j <= n1; ++j) {
      std::map<std::pair<std::size_t, std::size_t>, std::size_t> next;
      if (j < n1)
        for (std::size_t i = 0; i < n0;) {
          if (mult[j * n0 + i] < m) {
            ++i;
            continue;
          }
          std::size_t e = i;
          while (e < n0 && mult[j * n0 + e] >= m) ++e;
          const auto it = open.find({i, e});
          next[{i, e}] = it == open.end() ? j : it->second;
          i = e;
        }
      for (const auto& [run, j0] : open)
        if (!next.count(run) || next.at(run) != j0) emit(run.first, run.second, j0, j);
      open = std::move(next);
    }
  }
}

}  // namespace

template <int D>
std::vector<MeshRectangle<D>> knot_line_mesh(std::span<const LRBSpline<D>> basis) {
  std::map<std::pair<int, double>, std::vector<MeshRectangle<D>>> planes;
  for (const auto& b : basis) {
    const Box<D> sup = b.support();
    for (int k = 0; k < D; ++k) {
      const auto& t = b.knots[static_cast<std::size_t>(k)];
      for (std::size_t j = 0; j < t.size();) {
        std::size_t e = j;
        while (e < t.size() && t[e] == t[j]) ++e;
        planes[{k, t[j]}].push_back(MeshRectangle<D>::make(k, t[j], sup.lo, sup.hi, static_cast<int>(e - j)));
        j = e;
      }
    }
  }
  std::vector<MeshRectangle<D>> mesh;
  for (const auto& [key, rects] : planes) merge_plane<D>(key.first, key.second, rects, mesh);
  return mesh;
}

template std::vector<MeshRectangle<2>> knot_line_mesh(std::span<const LRBSpline<2>>);
template std::vector<MeshRectangle<3>> knot_line_mesh(std::span<const LRBSpline<3>>);

}  // namespace trivar
