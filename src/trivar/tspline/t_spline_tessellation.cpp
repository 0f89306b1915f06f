#include "trivar/tspline/t_spline_tessellation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "trivar/core/clamped_count.hpp"
#include "trivar/core/error.hpp"
#include "trivar/core/memory_budget.hpp"
#include "trivar/core/parallel.hpp"
#include "trivar/spline/second_derivative_bound.hpp"

namespace trivar {

namespace {

// The sub-cell counts (n_u, n_v) of an element. A triangle whose vertices span at most h_u = 1 / n_u and
// h_v = 1 / n_v (element units) deviates from the patch by at most
//   e = (D_uu h_u^2 + 2 D_uv h_u h_v + D_vv h_v^2) / 8:
// at a point x = sum l_i x_i of it, Taylor's theorem with the integral remainder about x gives
// f(x) - sum l_i f(x_i) = -sum l_i int_0^1 (1 - r) d_i^T H d_i dr with d_i = x_i - x, so
// |e| <= 1/2 sum l_i (D_uu d_iu^2 + 2 D_uv |d_iu d_iv| + D_vv d_iv^2); sum l_i d_iu^2 is the variance of the
// vertices' u under the weights l, at most h_u^2 / 4, and sum l_i |d_iu d_iv| <= h_u h_v / 4 by Cauchy-Schwarz.
// The whole sum is held to the tolerance (not each term to a third of it): the pair with the fewest sub-cells,
// the smaller bound among equal counts. When no pair up to max_n meets it, the finest count in every direction
// whose terms are not zero.
std::array<int, 2> element_counts(const SecondDerivativeBound& D, double tol, int max_n) {
  const auto bound = [&](double a, double b) { return (D.uu / (a * a) + 2 * D.uv / (a * b) + D.vv / (b * b)) / 8; };
  std::array<int, 2> best{0, 0};
  double best_cells = std::numeric_limits<double>::infinity(), best_bound = 0;
  // n_u must leave room for the other terms: D_uu / (8 n_u^2) < tol.
  for (int a = clamped_count(std::sqrt(D.uu / (8 * tol)), 1, max_n); a <= max_n && a < best_cells; ++a) {
    // The smallest n_v: x = 1 / n_v solves D_vv x^2 + B x + c <= 0 with B = 2 D_uv / n_u, c = D_uu / n_u^2 - 8 tol.
    const double B = 2 * D.uv / a, c = D.uu / (double(a) * a) - 8 * tol;
    if (!(c < 0)) continue;
    const double root_inverse = (B + std::sqrt(B * B - 4 * D.vv * c)) / (-2 * c);  // 1 / (the positive root)
    int b = clamped_count(root_inverse, 1, max_n);
    while (b < max_n && bound(a, b) > tol) ++b;  // rounding
    const double e = bound(a, b);
    if (!(e <= tol)) continue;
    const double cells = double(a) * b;
    if (cells < best_cells || (cells == best_cells && e < best_bound)) {
      best = {a, b};
      best_cells = cells;
      best_bound = e;
    }
  }
  if (best[0] > 0) return best;
  return {D.uu != 0 || D.uv != 0 ? max_n : 1, D.vv != 0 || D.uv != 0 ? max_n : 1};  // NaN counts as not zero
}

// Triangles between the outer row o (an element side: o.size() - 1 equal steps, listed counter-clockwise round
// the element) and the inner row in (the element's lattice points one lattice step inside, at 1 .. n - 1 of its
// n steps along the side), always advancing the row whose next point comes first along the side. Let h be the
// larger of the two steps: at most 1 / (the element's own count along the side), as the side is sampled at
// least that finely and the lattice too. The current points o_k, in_r start h apart at most (0 and 1 / n) and
// stay so (the one advanced does not pass the other's next point), and a triangle spans
// max(step, |o_k - in_r|) <= h along the side and one lattice step across: the bound of element_counts holds.
// Counter-clockwise: o runs counter-clockwise round the element and in lies inside.
void zip(const std::vector<int>& o, const std::vector<int>& in, int n, std::vector<std::array<int, 3>>& out) {
  const long long mo = static_cast<long long>(o.size()) - 1, last = static_cast<long long>(in.size()) - 1;
  long long k = 0, r = 0;
  while (k < mo || r < last) {
    // Next positions: (k + 1) / mo outside, (r + 2) / n inside.
    if (r == last || (k < mo && (k + 1) * n <= (r + 2) * mo)) {
      out.push_back({o[static_cast<std::size_t>(k)], o[static_cast<std::size_t>(k + 1)], in[static_cast<std::size_t>(r)]});
      ++k;
    } else {
      out.push_back({o[static_cast<std::size_t>(k)], in[static_cast<std::size_t>(r + 1)], in[static_cast<std::size_t>(r)]});
      ++r;
    }
  }
}

}  // namespace

TSplineTriangulation tessellate(const TSplineSurface& surface, double tolerance, int max_per_element, int threads) {
  require(tolerance > 0 && std::isfinite(tolerance), "tessellate: the chordal tolerance must be positive");
  require(max_per_element >= 1, "tessellate: at least one subdivision per element");
  // The grid lines, from the elements (they are its cells, so neighbours share whole sides).
  const auto& elements = surface.elements();
  std::array<std::vector<double>, 2> lines;
  for (const Box<2>& e : elements)
    for (int k = 0; k < 2; ++k) {
      lines[k].push_back(e.lo[k]);
      lines[k].push_back(e.hi[k]);
    }
  for (auto& l : lines) {
    std::sort(l.begin(), l.end());
    l.erase(std::unique(l.begin(), l.end()), l.end());
  }
  const std::size_t nu = lines[0].size() - 1, nv = lines[1].size() - 1;
  const auto line = [&](int k, double x) {
    return static_cast<std::size_t>(std::lower_bound(lines[k].begin(), lines[k].end(), x) - lines[k].begin());
  };
  // Each element's own counts (its sub-cells), in parallel: the bound reads the whole Bezier net.
  const auto& nets = surface.bezier_elements();
  std::vector<std::array<int, 2>> own(elements.size());
  parallel_for(static_cast<std::ptrdiff_t>(elements.size()), threads, [&](std::ptrdiff_t e) {
    own[static_cast<std::size_t>(e)] = element_counts(second_derivative_bound(nets[static_cast<std::size_t>(e)]), tolerance, max_per_element);
  });
  // Every side (of a grid cell) is sampled once for both elements on it, as finely as the finer one needs: the
  // sides along s (index column + nu * line), the sides along t (line + (nu + 1) * row).
  std::vector<int> side_s(nu * (nv + 1), 0), side_t((nu + 1) * nv, 0);
  std::vector<std::array<std::size_t, 2>> cell(elements.size());
  for (std::size_t e = 0; e < elements.size(); ++e) {
    const std::size_t i = line(0, elements[e].lo[0]), j = line(1, elements[e].lo[1]);
    cell[e] = {i, j};
    for (std::size_t jj : {j, j + 1}) side_s[i + nu * jj] = std::max(side_s[i + nu * jj], own[e][0]);
    for (std::size_t ii : {i, i + 1}) side_t[ii + (nu + 1) * j] = std::max(side_t[ii + (nu + 1) * j], own[e][1]);
  }
  // An element whose sides all have its own counts is its lattice; otherwise its lattice (at least 2 x 2, so it
  // has inner points) is kept one step away from the sides, and the ring between is zipped to each side.
  const auto sides = [&](std::size_t e) {
    const auto [i, j] = cell[e];
    return std::array<int, 4>{side_s[i + nu * j], side_t[i + 1 + (nu + 1) * j], side_s[i + nu * (j + 1)], side_t[i + (nu + 1) * j]};
  };
  std::vector<std::array<int, 2>> lattice(elements.size());
  std::vector<char> regular(elements.size());
  double points = 0, triangles = 0;
  std::vector<char> corner_used((nu + 1) * (nv + 1), 0);
  for (std::size_t e = 0; e < elements.size(); ++e) {
    const auto m = sides(e);
    regular[e] = m[0] == own[e][0] && m[2] == own[e][0] && m[1] == own[e][1] && m[3] == own[e][1];
    const int a = regular[e] ? own[e][0] : std::max(own[e][0], 2), b = regular[e] ? own[e][1] : std::max(own[e][1], 2);
    lattice[e] = {a, b};
    points += (a - 1.0) * (b - 1.0);
    triangles += regular[e] ? 2.0 * a * b : m[0] + m[1] + m[2] + m[3] + 2.0 * (a - 2) + 2.0 * (b - 2) + 2.0 * (a - 2) * (b - 2);
    const auto [i, j] = cell[e];
    for (std::size_t c : {i + (nu + 1) * j, i + 1 + (nu + 1) * j, i + (nu + 1) * (j + 1), i + 1 + (nu + 1) * (j + 1)}) corner_used[c] = 1;
  }
  for (char c : corner_used) points += c;
  for (const auto* s : {&side_s, &side_t})
    for (int m : *s) points += std::max(m - 1, 0);
  require_memory(points * (24.0 + 16 + 4) + triangles * 12.0 + 4.0 * static_cast<double>(side_s.size() + side_t.size() + corner_used.size()),
                 "a T-spline tessellation of " + std::to_string(static_cast<long long>(points)) + " points and " +
                     std::to_string(static_cast<long long>(triangles)) + " triangles");

  TSplineTriangulation out;
  out.params.reserve(static_cast<std::size_t>(points));
  out.triangles.reserve(static_cast<std::size_t>(triangles));
  std::vector<int> owner;
  owner.reserve(static_cast<std::size_t>(points));
  const auto add_point = [&](double s, double t, std::size_t e) {
    out.params.push_back({s, t});
    owner.push_back(static_cast<int>(e));
    return static_cast<int>(out.params.size()) - 1;
  };
  std::vector<int> corner_id(corner_used.size(), -1), side_s_id(side_s.size(), -1), side_t_id(side_t.size(), -1);
  const auto corner = [&](std::size_t i, std::size_t j, std::size_t e) {
    int& id = corner_id[i + (nu + 1) * j];
    if (id < 0) id = add_point(lines[0][i], lines[1][j], e);
    return id;
  };
  // The points of side `index` in direction k (0: along s) from (i, j), in increasing order, into ids.
  const auto side = [&](int k, std::size_t index, std::size_t i, std::size_t j, std::size_t e, std::vector<int>& ids) {
    const int m = (k == 0 ? side_s : side_t)[index];
    int& first = (k == 0 ? side_s_id : side_t_id)[index];
    const double lo = lines[k][k == 0 ? i : j], hi = lines[k][(k == 0 ? i : j) + 1], other = lines[1 - k][k == 0 ? j : i];
    if (first < 0 && m > 1) {
      first = static_cast<int>(out.params.size());
      for (int r = 1; r < m; ++r) {
        const double x = lo + (hi - lo) * r / m;
        add_point(k == 0 ? x : other, k == 0 ? other : x, e);
      }
    }
    ids.clear();
    ids.push_back(corner(i, j, e));
    for (int r = 1; r < m; ++r) ids.push_back(first + r - 1);
    ids.push_back(k == 0 ? corner(i + 1, j, e) : corner(i, j + 1, e));
  };
  std::array<std::vector<int>, 4> ring;  // bottom, right, top, left: increasing s or t
  std::vector<int> inner;
  for (std::size_t e = 0; e < elements.size(); ++e) {
    const auto [i, j] = cell[e];
    side(0, i + nu * j, i, j, e, ring[0]);
    side(1, i + 1 + (nu + 1) * j, i + 1, j, e, ring[1]);
    side(0, i + nu * (j + 1), i, j + 1, e, ring[2]);
    side(1, i + (nu + 1) * j, i, j, e, ring[3]);
    const int a = lattice[e][0], b = lattice[e][1];
    const Box<2>& box = elements[e];
    const int base = static_cast<int>(out.params.size());
    for (int y = 1; y < b; ++y)
      for (int x = 1; x < a; ++x)
        add_point(box.lo[0] + box.extent(0) * x / a, box.lo[1] + box.extent(1) * y / b, e);
    const auto at = [&](int x, int y) {  // lattice point (x, y)
      if (y == 0) return ring[0][static_cast<std::size_t>(x)];
      if (y == b) return ring[2][static_cast<std::size_t>(x)];
      if (x == 0) return ring[3][static_cast<std::size_t>(y)];
      if (x == a) return ring[1][static_cast<std::size_t>(y)];
      return base + (x - 1) + (a - 1) * (y - 1);
    };
    const int margin = regular[e] ? 0 : 1;
    for (int y = margin; y < b - margin; ++y)
      for (int x = margin; x < a - margin; ++x) {
        out.triangles.push_back({at(x, y), at(x + 1, y), at(x + 1, y + 1)});
        out.triangles.push_back({at(x, y), at(x + 1, y + 1), at(x, y + 1)});
      }
    if (regular[e]) continue;
    // The ring, side by side counter-clockwise (top and left reversed).
    std::reverse(ring[2].begin(), ring[2].end());
    std::reverse(ring[3].begin(), ring[3].end());
    inner.clear();
    for (int x = 1; x < a; ++x) inner.push_back(at(x, 1));
    zip(ring[0], inner, a, out.triangles);
    inner.clear();
    for (int y = 1; y < b; ++y) inner.push_back(at(a - 1, y));
    zip(ring[1], inner, b, out.triangles);
    inner.clear();
    for (int x = a - 1; x >= 1; --x) inner.push_back(at(x, b - 1));
    zip(ring[2], inner, a, out.triangles);
    inner.clear();
    for (int y = b - 1; y >= 1; --y) inner.push_back(at(1, y));
    zip(ring[3], inner, b, out.triangles);
  }
  out.points.resize(out.params.size());
  parallel_for(static_cast<std::ptrdiff_t>(out.params.size()), threads, [&](std::ptrdiff_t i) {
    const auto& u = out.params[static_cast<std::size_t>(i)];
    surface.eval_on_element(owner[static_cast<std::size_t>(i)], {u[0], u[1]}, out.points[static_cast<std::size_t>(i)].data());
  });
  return out;
}

}  // namespace trivar
