#include "trivar/model/point_clusters.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "trivar/core/union_find.hpp"

namespace trivar {

std::vector<int> cluster_points(const std::vector<std::array<double, 3>>& p, double tol) {
  const int n = static_cast<int>(p.size());
  std::vector<int> order(p.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return p[static_cast<std::size_t>(a)][0] < p[static_cast<std::size_t>(b)][0]; });
  UnionFind uf(n);
  for (std::size_t i = 0; i < order.size(); ++i) {
    const auto& a = p[static_cast<std::size_t>(order[i])];
    for (std::size_t j = i + 1; j < order.size() && p[static_cast<std::size_t>(order[j])][0] - a[0] <= tol; ++j) {
      const auto& b = p[static_cast<std::size_t>(order[j])];
      if (std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]) <= tol) uf.unite(order[i], order[j]);
    }
  }
  std::vector<int> id(p.size(), -1), out(p.size());
  int next = 0;
  for (int i = 0; i < n; ++i) {
    int& r = id[static_cast<std::size_t>(uf.find(i))];
    if (r < 0) r = next++;
    out[static_cast<std::size_t>(i)] = r;
  }
  return out;
}

}  // namespace trivar
