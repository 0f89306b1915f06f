#include "trivar/tspline/subdivided_face.hpp"

#include <algorithm>
#include <map>
#include <string>
#include <utility>

#include "trivar/core/error.hpp"
#include "trivar/tspline/catmull_clark_patch.hpp"
#include "trivar/tspline/homogeneous_point.hpp"
#include "trivar/tspline/t_mesh_surface.hpp"

namespace trivar {

namespace {

// The subdivided neighbourhood: points and counter-clockwise quadrilaterals, with each directed edge's quad and
// the position of its start in it.
struct LocalQuads {
  std::vector<HomogeneousPoint> points;
  std::vector<std::array<int, 4>> quads;
  std::map<std::pair<int, int>, std::pair<int, int>> edges;

  void add(const std::array<int, 4>& q) {
    for (int i = 0; i < 4; ++i)
      edges[{q[static_cast<std::size_t>(i)], q[static_cast<std::size_t>((i + 1) % 4)]}] = {static_cast<int>(quads.size()), i};
    quads.push_back(q);
  }
  // The quad holding the directed edge a -> b, its loop from a.
  std::array<int, 4> from(int a, int b) const {
    const auto it = edges.find({a, b});
    require(it != edges.end(), "the subdivided neighbourhood does not close around the face");
    const auto& q = quads[static_cast<std::size_t>(it->second.first)];
    std::array<int, 4> r{};
    for (int i = 0; i < 4; ++i) r[static_cast<std::size_t>(i)] = q[static_cast<std::size_t>((it->second.second + i) % 4)];
    return r;
  }
};

// The 2N + 8 points (catmull_clark_patch layout) around corner v of the local quad (v, e0, d0, e1).
std::vector<int> gather_local(const LocalQuads& lq, const std::array<int, 4>& quad) {
  const int v = quad[0];
  std::vector<int> p{v};
  std::array<int, 4> q = quad;
  do {
    p.push_back(q[1]);
    p.push_back(q[2]);
    q = lq.from(v, q[3]);  // the next face counter-clockwise shares the edge v e_(i+1)
  } while (q[1] != quad[1] && p.size() <= 129);
  require(q[1] == quad[1], "a subdivided vertex has more than 64 faces");
  const int n = static_cast<int>(p.size() - 1) / 2;
  const int e0 = p[1], d0 = p[2], e1 = p[3], d1 = p[4], dm = p[static_cast<std::size_t>(2 * n)];
  const auto o1 = lq.from(d0, e0), o3 = lq.from(e1, d0), o2 = lq.from(d0, o1[3]), o4 = lq.from(e0, dm), o5 = lq.from(d1, e1);
  // Four faces around e_0, d_0 and e_1 (always so after a step: edge and face points of quadrilaterals).
  require(o2[3] == o3[2] && o4[3] == o1[2] && o5[2] == o3[3], "a subdivided edge or face point is not regular");
  for (int x : {o4[2], o1[2], o1[3], o2[2], o3[2], o3[3], o5[3]}) p.push_back(x);
  return p;
}

}  // namespace

SubdividedFace::SubdividedFace(const TMesh& m, int face) {
  const auto L = [&](int l) -> const TMeshLink& { return m.links[static_cast<std::size_t>(l)]; };
  const auto loop_of = [&](int f) -> const std::vector<int>& { return m.faces[static_cast<std::size_t>(f)]; };
  // The links leaving a vertex, one per face counter-clockwise, from link l0.
  const auto around = [&](int l0) {
    std::vector<int> ring;
    int l = l0;
    do {
      require(L(l).face >= 0 && loop_of(L(l).face).size() == 4, [&] {
        return "a face at vertex " + std::to_string(L(l0).vertex) + " is not a quadrilateral, or the vertex is on the boundary; "
               "the local Catmull-Clark step needs quadrilaterals within two face rings";
      });
      ring.push_back(l);
      l = L(L(l).prev).opp;
    } while (l != l0 && ring.size() <= 64);
    require(l == l0, [&] { return "vertex " + std::to_string(L(l0).vertex) + " has more than 64 faces"; });
    return ring;
  };
  require(loop_of(face).size() == 4, "the face is not a quadrilateral");
  // The first ring: the faces sharing a vertex with the face (their sub-faces hold every sub-face's 2N + 8 points).
  // The vertex points of their corners take the second ring (checked by `around`).
  std::vector<int> ring1;
  for (int l : loop_of(face))
    for (int k : around(l))
      if (std::find(ring1.begin(), ring1.end(), L(k).face) == ring1.end()) ring1.push_back(L(k).face);

  const auto point = [&](int x) -> HomogeneousPoint {
    const TMeshVertex& mv = m.vertices[static_cast<std::size_t>(x)];
    require(mv.primary >= 0 && mv.block.empty(), [&] {
      return "vertex " + std::to_string(x) + " has no control point or repeated-knot nodes; the local Catmull-Clark step needs one point per vertex";
    });
    const RationalPoint& pt = m.points[static_cast<std::size_t>(mv.primary)];
    rational_ = rational_ || pt.w != 1.0;
    return homogeneous(pt);
  };
  const auto face_point = [&](int f) {
    HomogeneousPoint s{};
    for (int l : loop_of(f)) {
      const HomogeneousPoint x = point(L(l).vertex);
      for (std::size_t c = 0; c < 4; ++c) s[c] += 0.25 * x[c];
    }
    return s;
  };
  // Textbook uniform Catmull-Clark (written here: no packaged library evaluates a subdivision step on this mesh).
  LocalQuads lq;
  std::map<std::pair<int, int>, int> id;  // (0 vertex | 1 edge | 2 face, mesh id) -> local point
  const auto local = [&](int kind, int x, auto&& make) {
    const auto [it, fresh] = id.emplace(std::pair{kind, x}, static_cast<int>(lq.points.size()));
    if (fresh) lq.points.push_back(make());
    return it->second;
  };
  const auto vertex_point = [&](int l0) {
    return local(0, L(l0).vertex, [&] {
      const std::vector<int> ring = around(l0);
      const double n = static_cast<double>(ring.size());
      // (F + 2 R + (n - 3) P) / n = (n - 2) / n P + (sum of edge neighbours + sum of face points) / n^2
      HomogeneousPoint r = point(L(l0).vertex);
      for (double& c : r) c *= (n - 2) / n;
      for (int l : ring) {
        const HomogeneousPoint e = point(L(L(l).next).vertex), f = face_point(L(l).face);
        for (std::size_t c = 0; c < 4; ++c) r[c] += (e[c] + f[c]) / (n * n);
      }
      return r;
    });
  };
  const auto edge_point = [&](int l) {
    return local(1, L(l).edge, [&] {
      const HomogeneousPoint a = point(L(l).vertex), b = point(L(L(l).next).vertex), f = face_point(L(l).face),
                          g = face_point(L(L(l).opp).face);
      HomogeneousPoint r{};
      for (std::size_t c = 0; c < 4; ++c) r[c] = (a[c] + b[c] + f[c] + g[c]) / 4;
      return r;
    });
  };
  // The sub-faces of the first ring: at corner i of face g, (vertex point, edge point of the side to corner i + 1,
  // face point, edge point of the side from corner i - 1), counter-clockwise like g.
  std::array<std::array<int, 4>, 4> own{};
  for (int g : ring1) {
    const auto& loop = loop_of(g);
    const int fp = local(2, g, [&] { return face_point(g); });
    // The face's corners from its first corner link, as its (u, v) numbers them.
    const std::size_t start = static_cast<std::size_t>(std::find(loop.begin(), loop.end(), m.first_corner(g)) - loop.begin());
    for (std::size_t i = 0; i < 4; ++i) {
      const int l = loop[(start + i) % 4], back = loop[(start + i + 3) % 4];
      const std::array<int, 4> q{vertex_point(l), edge_point(l), fp, edge_point(back)};
      lq.add(q);
      if (g == face) own[i] = q;
    }
  }
  for (std::size_t q = 0; q < 4; ++q) {
    Quarter& z = quarters_[q];
    const std::vector<int> idx = gather_local(lq, own[q]);
    z.valence = static_cast<int>(idx.size() - 8) / 2;
    for (int x : idx) {
      const HomogeneousPoint& h = lq.points[static_cast<std::size_t>(x)];
      z.points.push_back(h);
      z.wx.push_back({h[0], h[1], h[2]});
      z.w.push_back({h[3], 0, 0});
    }
  }
}

void SubdividedFace::eval_quarter(int quarter, double s, double t, double* out) const {
  const Quarter& z = quarters_[static_cast<std::size_t>(quarter)];
  // The rules are linear: once on w x, once on the weights (all 1: W = 1, W' = 0).
  const auto run = [&](const std::vector<std::array<double, 3>>& p, double* q) {
    if (z.valence == 4)
      eval_uniform_bicubic(regular_grid(p), s, t, q);
    else
      catmull_clark_patch(z.valence).eval(p, s, t, q);
  };
  double x[9], w[9] = {1, 0, 0, 0, 0, 0, 0, 0, 0};
  run(z.wx, x);
  if (rational_) run(z.w, w);
  for (int k = 0; k < 3; ++k) {
    for (int c = 0; c < 3; ++c) out[4 * k + c] = x[3 * k + c];
    out[4 * k + 3] = w[3 * k];
  }
}

void SubdividedFace::eval(double u, double v, double* out) const {
  const int q = u < 0.5 ? (v < 0.5 ? 0 : 3) : (v < 0.5 ? 1 : 2);
  const CornerFrame fr = corner_frame(q);
  const double du = u - fr.origin[0], dv = v - fr.origin[1];
  const double s = std::clamp(2 * (fr.a[0] * du + fr.a[1] * dv), 0.0, 1.0), t = std::clamp(2 * (fr.b[0] * du + fr.b[1] * dv), 0.0, 1.0);
  double h[12];
  eval_quarter(q, s, t, h);
  for (int c = 0; c < 4; ++c) {
    out[c] = h[c];
    out[4 + c] = 2 * (fr.a[0] * h[4 + c] + fr.b[0] * h[8 + c]);
    out[8 + c] = 2 * (fr.a[1] * h[4 + c] + fr.b[1] * h[8 + c]);
  }
}

}  // namespace trivar
