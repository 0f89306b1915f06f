#pragma once
// Rays in a T-image (Sederberg et al. 2003): the knot lines met by a ray from a point along s or t, and
// whether a point lies in the T-faces (where rays stop). Used by the local knot vectors and the T-junction
// extensions.
#include <algorithm>
#include <array>
#include <map>
#include <vector>

#include "trivar/tspline/t_image.hpp"

namespace trivar {

// The T-image edges as knot lines: for each axis k, the edges perpendicular to it grouped by their coordinate
// along k, sorted, each line a list of closed intervals in the other parameter. A ray along k from x on the
// line y meets the nearest line beyond x holding an interval that contains y.
class KnotRays {
public:
  explicit KnotRays(const TImage& im) {
    std::array<std::map<double, std::vector<std::array<double, 2>>>, 2> by;
    for (int e = 0; e < static_cast<int>(im.edges.size()); ++e) {
      const Box<2> b = im.edge_box(e);
      const int k = b.lo[0] == b.hi[0] ? 0 : 1;  // a vertical edge is a knot line of s
      by[k][b.lo[k]].push_back({b.lo[1 - k], b.hi[1 - k]});
    }
    for (int k = 0; k < 2; ++k)
      for (auto& [c, spans] : by[k]) lines_[k].push_back({c, std::move(spans)});
    // The faces on the grid of the vertices' coordinates, to tell where the domain ends.
    for (int k = 0; k < 2; ++k) {
      for (const TVertex& v : im.vertices) grid_[k].push_back(k == 0 ? v.s : v.t);
      std::sort(grid_[k].begin(), grid_[k].end());
      grid_[k].erase(std::unique(grid_[k].begin(), grid_[k].end()), grid_[k].end());
    }
    const std::size_t nu = grid_[0].size() - 1;
    covered_.assign(nu * (grid_[1].size() - 1), 0);
    for (int f = 0; f < static_cast<int>(im.faces.size()); ++f) {
      const Box<2> b = im.face_box(f);
      std::array<std::size_t, 4> r;
      for (int k = 0; k < 2; ++k) {
        r[2 * k] = index(k, b.lo[k]);
        r[2 * k + 1] = index(k, b.hi[k]);
      }
      for (std::size_t j = r[2]; j < r[3]; ++j)
        for (std::size_t i = r[0]; i < r[1]; ++i) covered_[i + nu * j] = 1;
    }
  }

  // Whether the point lies in a face (closed: points on a face's boundary count).
  bool inside(double s, double t) const {
    const std::array<double, 2> u{s, t};
    std::array<std::array<std::ptrdiff_t, 2>, 2> cells;  // per direction the cells whose closure holds u
    for (int k = 0; k < 2; ++k) {
      const auto& g = grid_[k];
      if (u[k] < g.front() || u[k] > g.back()) return false;
      const auto last = static_cast<std::ptrdiff_t>(g.size()) - 2;
      const auto i = static_cast<std::ptrdiff_t>(std::upper_bound(g.begin(), g.end(), u[k]) - g.begin()) - 1;
      const std::ptrdiff_t below = g[static_cast<std::size_t>(i)] == u[k] && i > 0 ? i - 1 : std::min(i, last);
      cells[k] = {below, std::min(i, last)};
    }
    const std::size_t nu = grid_[0].size() - 1;
    for (std::ptrdiff_t i : cells[0])
      for (std::ptrdiff_t j : cells[1])
        if (covered_[static_cast<std::size_t>(i) + nu * static_cast<std::size_t>(j)]) return true;
    return false;
  }

  // The next knot line along axis k in direction sign (+1, -1) strictly beyond x, on the line y; x itself when
  // there is none.
  double next(int k, int sign, double x, double y) const {
    const auto& L = lines_[k];
    auto it = std::upper_bound(L.begin(), L.end(), x, [](double v, const Line& l) { return v < l.c; });
    if (sign > 0) {
      for (; it != L.end(); ++it)
        if (it->covers(y)) return it->c;
    } else {
      auto r = std::make_reverse_iterator(it);
      for (; r != L.rend(); ++r)
        if (r->c < x && r->covers(y)) return r->c;
    }
    return x;
  }

private:
  std::size_t index(int k, double x) const {
    return static_cast<std::size_t>(std::lower_bound(grid_[k].begin(), grid_[k].end(), x) - grid_[k].begin());
  }
  std::array<std::vector<double>, 2> grid_;
  std::vector<char> covered_;
  struct Line {
    double c;
    std::vector<std::array<double, 2>> spans;
    bool covers(double y) const {
      return std::any_of(spans.begin(), spans.end(), [y](const auto& s) { return s[0] <= y && y <= s[1]; });
    }
  };
  std::array<std::vector<Line>, 2> lines_;
};

}  // namespace trivar
