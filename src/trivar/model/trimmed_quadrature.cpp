#include "trivar/model/trimmed_quadrature.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "trivar/core/error.hpp"
#include "trivar/core/gauss_legendre.hpp"

namespace trivar {

namespace {

void gauss_box(const Box<3>& b, const QuadratureRule& r, std::vector<VolumePoint>& out) {
  const std::size_t n = r.nodes.size();
  for (std::size_t k = 0; k < n; ++k)
    for (std::size_t j = 0; j < n; ++j)
      for (std::size_t i = 0; i < n; ++i)
        out.push_back({{b.lo[0] + b.extent(0) * r.nodes[i], b.lo[1] + b.extent(1) * r.nodes[j],
                        b.lo[2] + b.extent(2) * r.nodes[k]},
                       b.extent(0) * b.extent(1) * b.extent(2) * r.weights[i] * r.weights[j] * r.weights[k]});
}

// Sorted breakpoints of [lo, hi]: the ends and the crossings of the line through p along `axis` inside.
void add_crossings(const TrimmedSolid& s, int axis, const std::array<double, 3>& p, double lo, double hi,
                   std::vector<LineCrossing>& cs, std::vector<double>& out) {
  s.axis_crossings(axis, p, lo, hi, cs);
  for (const LineCrossing& c : cs) out.push_back(c.t);
}

void finish(std::vector<double>& cuts, double lo, double hi) {
  cuts.push_back(lo);
  cuts.push_back(hi);
  std::sort(cuts.begin(), cuts.end());
}

// The Gauss lines along axis a through a cut leaf, one dimension at a time (a simplified form of Saye's scheme
// for implicitly defined domains): what a line sees (its crossings) is smooth in the other two coordinates b, c
// except where the boundary crosses the leaf's faces a = lo, a = hi, so each b-line of the base is split where
// it crosses the boundary on those faces, and the c-range where those kink curves reach the faces b = lo,
// b = hi. Calls line(p, w, crossings) with p[b], p[c] set and the base weight w.
template <class Line>
void for_each_line(const TrimmedSolid& s, const Box<3>& box, int a, const QuadratureRule& r, Line&& line) {
  thread_local std::vector<LineCrossing> cs;
  const int b = (a + 1) % 3, c = (a + 2) % 3;
  const std::size_t n = r.nodes.size();
  std::vector<double> cc, bb;
  std::array<double, 3> p{};
  for (double pa : {box.lo[a], box.hi[a]})
    for (double pb : {box.lo[b], box.hi[b]}) {
      p[a] = pa;
      p[b] = pb;
      add_crossings(s, c, p, box.lo[c], box.hi[c], cs, cc);
    }
  finish(cc, box.lo[c], box.hi[c]);
  for (std::size_t ci = 0; ci + 1 < cc.size(); ++ci) {
    const double c0 = cc[ci], hc = cc[ci + 1] - c0;
    if (hc <= 0) continue;
    for (std::size_t j = 0; j < n; ++j) {
      p[c] = c0 + hc * r.nodes[j];
      bb.clear();
      for (double pa : {box.lo[a], box.hi[a]}) {
        p[a] = pa;
        add_crossings(s, b, p, box.lo[b], box.hi[b], cs, bb);
      }
      finish(bb, box.lo[b], box.hi[b]);
      for (std::size_t bi = 0; bi + 1 < bb.size(); ++bi) {
        const double b0 = bb[bi], hb = bb[bi + 1] - b0;
        if (hb <= 0) continue;
        for (std::size_t i = 0; i < n; ++i) {
          p[b] = b0 + hb * r.nodes[i];
          s.axis_crossings(a, p, box.lo[a], box.hi[a], cs);
          line(p, hb * hc * r.weights[i] * r.weights[j], std::as_const(cs));
        }
      }
    }
  }
}

// The inside intervals of one line along axis a (crossings cs, base weight w), Gauss on each.
void volume_line(const TrimmedSolid& s, const Box<3>& box, int a, const QuadratureRule& r, std::array<double, 3> p,
                 double w, const std::vector<LineCrossing>& cs, std::vector<double>& cuts, std::vector<VolumePoint>& out) {
  cuts.clear();
  for (const LineCrossing& c : cs) cuts.push_back(c.t);
  finish(cuts, box.lo[a], box.hi[a]);
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    const double lo = cuts[k], len = cuts[k + 1] - lo;
    if (len <= 0) continue;
    // Whether the interval is inside is asked of its midpoint, not read off the crossings' directions, so a
    // crossing lost at a silhouette costs accuracy but never flips a whole interval.
    p[a] = lo + len / 2;
    if (!s.contains(p)) continue;
    for (std::size_t q = 0; q < r.nodes.size(); ++q) {
      p[a] = lo + len * r.nodes[q];
      out.push_back({p, w * len * r.weights[q]});
    }
  }
}

// The boundary on one line along axis a: with the partition of unity w_a = n_a^4 / (n_x^4 + n_y^4 + n_z^4) over
// the axes, the surface integral is the sum over a of the integrals of w_a dS = w_a / |n_a| db dc over the base
// of the a-lines, one point per crossing. Faces parallel to a line contribute nothing to that axis's term, and
// near silhouettes the weight |n_a|^3 / sum n^4 vanishes smoothly instead of blowing up (so a crossing the mesh
// misses within the chordal tolerance of a silhouette costs next to nothing).
void surface_line(const TrimmedSolid& s, int a, std::array<double, 3> p, double w, const std::vector<LineCrossing>& cs,
                  const std::vector<char>& skip, std::vector<SurfacePoint>& out) {
  const TrimmedBoundary& bd = s.boundary();
  for (const LineCrossing& c : cs) {
    if (!skip.empty() && skip[static_cast<std::size_t>(c.face)]) continue;
    const TrimmedFace& f = bd.faces[static_cast<std::size_t>(c.face)];
    double d[9];
    f.surface.eval_derivs(c.uv, 1, d);
    std::array<double, 3> n{d[4] * d[8] - d[5] * d[7], d[5] * d[6] - d[3] * d[8], d[3] * d[7] - d[4] * d[6]};
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (len == 0) continue;
    for (double& x : n) x *= (f.reversed ? -1 : 1) / len;
    p[a] = c.t;
    const double n4 = n[0] * n[0] * n[0] * n[0] + n[1] * n[1] * n[1] * n[1] + n[2] * n[2] * n[2] * n[2];
    out.push_back({p, n, w * std::pow(std::abs(n[a]), 3) / n4});
  }
}

struct Sink {
  std::vector<VolumePoint>& volume;
  std::vector<SurfacePoint>* surface;
  const std::vector<char>& skip;
};

// A cut leaf: the volume on the lines along the transversal axis, the faces (when asked for) on the lines along
// every axis. The transversal axis's lines serve both, so their crossings are computed once.
void leaf(const TrimmedSolid& s, const Box<3>& box, const QuadratureRule& r, Sink& out) {
  const int t = s.transversal_axis(box);
  std::vector<double> cuts;
  for (int a = 0; a < 3; ++a) {
    if (a != t && !out.surface) continue;
    for_each_line(s, box, a, r, [&](const std::array<double, 3>& p, double w, const std::vector<LineCrossing>& cs) {
      if (a == t) volume_line(s, box, a, r, p, w, cs, cuts, out.volume);
      if (out.surface) surface_line(s, a, p, w, cs, out.skip, *out.surface);
    });
  }
}

BoxPlacement place(const TrimmedSolid& s, const Box<3>& b) {
  if (s.boundary_meets(b)) return BoxPlacement::cut;
  return s.contains(b.center()) ? BoxPlacement::inside : BoxPlacement::outside;
}

void subdivide(const TrimmedSolid& s, const Box<3>& b, const QuadratureRule& r, int depth, Sink& out) {
  if (depth == 0) {
    leaf(s, b, r, out);
    return;
  }
  const auto c = b.center();
  for (int o = 0; o < 8; ++o) {
    Box<3> child;
    for (int k = 0; k < 3; ++k) {
      const bool upper = (o >> k) & 1;
      child.lo[k] = upper ? c[k] : b.lo[k];
      child.hi[k] = upper ? b.hi[k] : c[k];
    }
    switch (place(s, child)) {
      case BoxPlacement::inside: gauss_box(child, r, out.volume); break;
      case BoxPlacement::outside: break;
      case BoxPlacement::cut: subdivide(s, child, r, depth - 1, out); break;
    }
  }
}

}  // namespace

BoxPlacement trimmed_box_quadrature(const TrimmedSolid& solid, const Box<3>& box, const TrimmedQuadratureOptions& opts,
                                    std::vector<VolumePoint>& volume, std::vector<SurfacePoint>* surface,
                                    const std::vector<char>& skip_faces) {
  require(opts.points >= 1 && opts.points <= 32 && opts.depth >= 0 && opts.depth <= 8,
          "trimmed quadrature: points must be in [1, 32] and the depth in [0, 8]");
  const BoxPlacement p = place(solid, box);
  Sink sink{volume, surface, skip_faces};
  if (p == BoxPlacement::cut) subdivide(solid, box, gauss_legendre(opts.points), opts.depth, sink);
  return p;
}

}  // namespace trivar
