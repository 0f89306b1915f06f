#include "trivar/tspline/tensor_t_spline.hpp"

#include <algorithm>

#include "trivar/core/error.hpp"

namespace trivar {

TSpline t_spline_from_tensor(const TensorSpline<2>& s) {
  require(s.dim() >= 1 && s.dim() <= 3,
          "T-spline from tensor: dimension " + std::to_string(s.dim()) + " (the T-pointset holds x, y, z)");
  std::array<std::vector<double>, 2> uniq;
  for (int k = 0; k < 2; ++k) {
    const KnotVector& kv = s.knots(k);
    const int p = kv.degree();
    uniq[k] = kv.unique();
    for (double u : uniq[k]) {
      const int m = kv.multiplicity(u);
      const bool end = u == uniq[k].front() || u == uniq[k].back();
      require(end ? m == p + 1 : m == 1, [&] {
        return "T-spline from tensor: direction " + std::string(k == 0 ? "s" : "t") + " knot " + std::to_string(u) +
               " has multiplicity " + std::to_string(m) + " (open ends and simple interior knots are required)";
      });
    }
  }
  TSpline ts;
  ts.degrees = {s.degree(0), s.degree(1)};
  const int nu = static_cast<int>(uniq[0].size()), nv = static_cast<int>(uniq[1].size());
  TImage& im = ts.image;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) im.vertices.push_back({uniq[0][i], uniq[1][j], {-1, -1, -1, -1}});
  const auto vid = [nu](int i, int j) { return i + nu * j; };
  std::vector<int> hlink(static_cast<std::size_t>(nu * nv), -1), vlink(static_cast<std::size_t>(nu * nv), -1);
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      if (i + 1 < nu) hlink[static_cast<std::size_t>(vid(i, j))] = add_edge(im, vid(i, j), vid(i + 1, j));
      if (j + 1 < nv) vlink[static_cast<std::size_t>(vid(i, j))] = add_edge(im, vid(i, j), vid(i, j + 1));
    }
  std::vector<int> face_of(static_cast<std::size_t>(nu * nv), -1);
  for (int j = 0; j + 1 < nv; ++j)
    for (int i = 0; i + 1 < nu; ++i) {
      face_of[static_cast<std::size_t>(vid(i, j))] = static_cast<int>(im.faces.size());
      im.faces.push_back({{hlink[static_cast<std::size_t>(vid(i, j))], vlink[static_cast<std::size_t>(vid(i + 1, j))],
                           hlink[static_cast<std::size_t>(vid(i, j + 1))] + 1, vlink[static_cast<std::size_t>(vid(i, j))] + 1}});
    }
  connect_vertex_links(im);

  // Per direction and B-spline index: the anchor's first grid line and whether it has a width.
  std::array<std::vector<std::array<int, 2>>, 2> anchor;
  for (int k = 0; k < 2; ++k) {
    const KnotVector& kv = s.knots(k);
    const int p = kv.degree();
    for (int a = 0; a < kv.size(); ++a) {
      const int c = a + (p + 1) / 2;  // centre knot (odd) or left end of the centre interval (even)
      const auto line = [&](int idx) {
        return static_cast<int>(std::lower_bound(uniq[k].begin(), uniq[k].end(), kv[idx]) - uniq[k].begin());
      };
      const int lo = p % 2 == 1 ? line(c) : line(a + p / 2), hi = p % 2 == 1 ? lo : line(a + p / 2 + 1);
      anchor[k].push_back({lo, hi - lo});
    }
  }
  const int ns = s.count(0), nt = s.count(1);
  ts.connect.nodes.resize(static_cast<std::size_t>(ns * nt));
  ts.pointset.points.resize(static_cast<std::size_t>(ns * nt));
  for (int b = 0; b < nt; ++b)
    for (int a = 0; a < ns; ++a) {
      const int id = a + ns * b;
      TNode& n = ts.connect.nodes[static_cast<std::size_t>(id)];
      const auto [i, wi] = anchor[0][static_cast<std::size_t>(a)];
      const auto [j, wj] = anchor[1][static_cast<std::size_t>(b)];
      if (wi == 0 && wj == 0) {
        n.kind = TAnchorKind::vertex;
        n.anchor = vid(i, j);
      } else if (wi == 0) {
        n.kind = TAnchorKind::link;
        n.anchor = vlink[static_cast<std::size_t>(vid(i, j))];
      } else if (wj == 0) {
        n.kind = TAnchorKind::link;
        n.anchor = hlink[static_cast<std::size_t>(vid(i, j))];
      } else {
        n.kind = TAnchorKind::face;
        n.anchor = face_of[static_cast<std::size_t>(vid(i, j))];
      }
      n.point = id;
      n.neighbours = {b + 1 < nt ? id + ns : -1, a > 0 ? id - 1 : -1, b > 0 ? id - ns : -1, a + 1 < ns ? id + 1 : -1};
      RationalPoint& p = ts.pointset.points[static_cast<std::size_t>(id)];
      p.w = s.weight(id);
      double x[3] = {0, 0, 0};
      s.control_point(id, x);
      p.xyz = {x[0], x[1], x[2]};
    }
  validate(ts);
  return ts;
}

}  // namespace trivar
