#pragma once
// Continuity across the interior edges of a quad T-mesh surface evaluated face by face (value, d/du, d/dv in
// each face's (u, v) in [0, 1]^2): positions, normals and cross-edge first derivatives from the two faces of
// every edge between quadrilaterals, at given positions strictly inside the edge; and a face evaluator's
// derivatives against central differences of its values.
#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "trivar/tspline/t_mesh.hpp"

namespace trivar::test {

struct Continuity {
  double gap = 0, normal_angle = 0, c1 = 0;  // position gap, sine of the normals' angle, relative C1 defect
  int edges = 0;
};

// The face-local (u, v) of position sigma along side k of a face (sides counter-clockwise from the first
// corner).
inline std::array<double, 2> side_uv(int k, double sigma) {
  switch (k) {
    case 0: return {sigma, 0};
    case 1: return {1, sigma};
    case 2: return {1 - sigma, 1};
    default: return {0, 1 - sigma};
  }
}

inline std::array<double, 3> unit_normal(const double* o) {
  const std::array<double, 3> n{o[4] * o[8] - o[5] * o[7], o[5] * o[6] - o[3] * o[8], o[3] * o[7] - o[4] * o[6]};
  const double l = std::hypot(n[0], n[1], n[2]);
  return {n[0] / l, n[1] / l, n[2] / l};
}

// The side of face f holding link l (quad faces and faces whose sides are single links).
inline int side_of(const TMesh& m, int f, int l) {
  const auto& loop = m.faces[static_cast<std::size_t>(f)];
  const auto first = std::find(loop.begin(), loop.end(), m.first_corner(f));
  int k = -1;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const int x = loop[(static_cast<std::size_t>(first - loop.begin()) + i) % loop.size()];
    if (m.links[static_cast<std::size_t>(x)].flag == 0) ++k;
    if (x == l) return k;
  }
  return -1;
}

inline std::vector<double> tenths() { return {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9}; }

// eval(face, u, v, out[9]); the edges `skip` (sharp creases) are left out.
template <class Eval>
Continuity continuity(const TMesh& m, const Eval& eval, const std::vector<double>& along = tenths(), const std::vector<int>& skip = {}) {
  Continuity c;
  for (int l = 0; l < static_cast<int>(m.links.size()); ++l) {
    const TMeshLink& a = m.links[static_cast<std::size_t>(l)];
    if (a.vertex < 0 || a.opp < 0 || std::find(skip.begin(), skip.end(), a.edge) != skip.end()) continue;
    const TMeshLink& b = m.links[static_cast<std::size_t>(a.opp)];
    if (a.face < 0 || b.face < 0 || l > a.opp) continue;
    if (m.faces[static_cast<std::size_t>(a.face)].size() != 4 || m.faces[static_cast<std::size_t>(b.face)].size() != 4) continue;
    ++c.edges;
    const int ka = side_of(m, a.face, l), kb = side_of(m, b.face, a.opp);
    for (double t : along) {
      const auto ua = side_uv(ka, t), ub = side_uv(kb, 1 - t);
      double x[9], y[9];
      eval(a.face, ua[0], ua[1], x);
      eval(b.face, ub[0], ub[1], y);
      c.gap = std::max(c.gap, std::hypot(x[0] - y[0], x[1] - y[1], x[2] - y[2]));
      const auto na = unit_normal(x), nb = unit_normal(y);
      c.normal_angle = std::max(c.normal_angle, std::hypot(na[1] * nb[2] - na[2] * nb[1], na[2] * nb[0] - na[0] * nb[2], na[0] * nb[1] - na[1] * nb[0]));
      // Inward derivatives: side 0 +v, 1 -u, 2 -v, 3 +u; C1 when they are opposite.
      const auto inward = [](int k, const double* o, int comp) {
        return k == 0 ? o[6 + comp] : k == 1 ? -o[3 + comp] : k == 2 ? -o[6 + comp] : o[3 + comp];
      };
      double d = 0, size = 0;
      for (int comp = 0; comp < 3; ++comp) {
        d = std::max(d, std::abs(inward(ka, x, comp) + inward(kb, y, comp)));
        size = std::max(size, std::abs(inward(ka, x, comp)));
      }
      c.c1 = std::max(c.c1, d / size);
    }
  }
  return c;
}

// The largest difference between eval's d/du, d/dv and central differences (step h) of its values, on `faces`
// at each (u, v) of `uv` (eval(face, u, v, out[9])).
template <class Eval>
double finite_difference_error(const Eval& eval, const std::vector<int>& faces, const std::vector<std::pair<double, double>>& uv,
                               double h = 1e-6) {
  double fd = 0;
  for (int f : faces)
    for (const auto& [u, v] : uv) {
      double x[9], a[9], b[9], c[9], d[9];
      eval(f, u, v, x);
      eval(f, u + h, v, a);
      eval(f, u - h, v, b);
      eval(f, u, v + h, c);
      eval(f, u, v - h, d);
      for (int k = 0; k < 3; ++k)
        fd = std::max({fd, std::abs((a[k] - b[k]) / (2 * h) - x[3 + k]), std::abs((c[k] - d[k]) / (2 * h) - x[6 + k])});
    }
  return fd;
}

}  // namespace trivar::test
