#include "trivar/model/boundary_tessellation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <sstream>
#include <string>

#include "trivar/core/error.hpp"
#include "trivar/core/memory_budget.hpp"
#include "trivar/core/vec3.hpp"

namespace trivar {

namespace {

using Vec = Vec3;
using Coord = std::int64_t;

// Cell corners are lattice indices in fixed point: kFrac bits below one lattice step leave room for that
// many halvings where a lattice cell is still too coarse.
constexpr int kFrac = 20;
constexpr Coord kStep = Coord{1} << kFrac;
// Breaks closer than this (in unit parameters) are one break.
constexpr double kSnap = 1e-12;
// Estimated memory per output triangle: the triangle (12 bytes), half a vertex with its origins here and in
// the model tessellation (about 40), a quarter cell and its corners in the point lists (about 40), with room
// for vector growth.
constexpr double kBytesPerTriangle = 120;


Vec at(const TensorSpline<2>& s, const Param<2>& u) {
  Vec x;
  s.eval(u, x.data());
  return x;
}

// Breakpoints of direction k mapped to [0, 1]: the places where the geometry may bend abruptly.
std::vector<double> unit_breaks(const TensorSpline<2>& s, int k) {
  std::vector<double> b = s.knots(k).breakpoints();
  const double lo = b.front(), len = b.back() - b.front();
  for (double& x : b) x = (x - lo) / len;
  b.front() = 0.0;
  b.back() = 1.0;
  return b;
}

std::vector<double> merged(std::vector<double> a, const std::vector<double>& b) {
  a.insert(a.end(), b.begin(), b.end());
  std::sort(a.begin(), a.end());
  a.erase(std::unique(a.begin(), a.end(), [](double x, double y) { return y - x <= kSnap; }), a.end());
  return a;
}

std::vector<double> flipped(std::vector<double> a) {
  for (double& x : a) x = 1.0 - x;
  std::reverse(a.begin(), a.end());
  return a;
}

// What the refinement needs to know of a parameter rectangle, from the surface and its first and second
// derivatives on a 3 x 3 grid of points.
struct CellMeasure {
  // Squared lengths of the rectangle's sides in coordinates in which the normal part of the second
  // derivative is bounded by the identity: the linear interpolant on a triangle inside the rectangle with
  // longest scaled edge e deviates from the surface by at most (1/2) (e^2 / 3) (see chord_bound).
  double wu = 0, wv = 0;
  double lu = 0, lv = 0;  // lengths in space of the longest row in u and column in v
};

CellMeasure measure(const TensorSpline<2>& s, const Param<2>& lo, const Param<2>& hi) {
  // Per point: x, x_u, x_v, x_uu, x_uv, x_vv (derivative_index.hpp ordering).
  std::array<std::array<double, 18>, 9> d;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i)
      s.eval_derivs({lo[0] + 0.5 * i * (hi[0] - lo[0]), lo[1] + 0.5 * j * (hi[1] - lo[1])}, 2,
                    d[i + 3 * j].data());
  CellMeasure m;
  for (int j = 0; j < 3; ++j) {
    double row = 0, col = 0;
    for (int i = 0; i < 2; ++i) {
      row += distance({d[i + 3 * j][0], d[i + 3 * j][1], d[i + 3 * j][2]},
                      {d[i + 1 + 3 * j][0], d[i + 1 + 3 * j][1], d[i + 1 + 3 * j][2]});
      col += distance({d[j + 3 * i][0], d[j + 3 * i][1], d[j + 3 * i][2]},
                      {d[j + 3 * (i + 1)][0], d[j + 3 * (i + 1)][1], d[j + 3 * (i + 1)][2]});
    }
    m.lu = std::max(m.lu, row);
    m.lv = std::max(m.lv, col);
  }
  // Distance from the surface is measured along the normal, so only the normal part of the second derivative
  // bends the triangles away from it (a flat face in any parametrisation needs no refinement). The normal
  // turns over the cell: the projection on the centre normal is widened by the largest turning angle times
  // the whole second derivative.
  const auto vec = [](const double* x) { return Vec{x[0], x[1], x[2]}; };
  const Vec nc = cross(vec(d[4].data() + 3), vec(d[4].data() + 6));
  const double ncl = norm(nc);
  double turn = ncl > 0 ? 0.0 : 1.0;
  for (const auto& p : d) {
    const Vec n = cross(vec(p.data() + 3), vec(p.data() + 6));
    const double nl = norm(n);
    if (ncl > 0 && nl > 0) turn = std::max(turn, norm(cross(n, nc)) / (nl * ncl));
  }
  std::array<double, 3> q{};  // bounds of |n . x_uu|, |n . x_uv|, |n . x_vv|
  for (const auto& p : d)
    for (int k = 0; k < 3; ++k) {
      const Vec x2 = vec(p.data() + 9 + 3 * k);
      const double normal = ncl > 0 ? std::abs(dot(x2, nc)) / ncl : 0.0;
      q[k] = std::max(q[k], normal + turn * norm(x2));
    }
  // a du^2 + 2 b du dv + c dv^2 <= (a + b) du^2 + (b + c) dv^2.
  const double du = hi[0] - lo[0], dv = hi[1] - lo[1];
  m.wu = (q[0] + q[1]) * du * du;
  m.wv = (q[1] + q[2]) * dv * dv;
  return m;
}

// Every triangle of a cell's fan (its centre to two consecutive points of its boundary, corners and at most
// one point inside each side) has scaled edges no longer than the larger of the scaled sides and the scaled
// half diagonal. For a point p of a triangle with vertices p_i and barycentric weights l_i, the linear
// interpolant deviates by (1/2) sum l_i (p_i - p)^T H (p_i - p), and sum l_i |p_i - p|^2 <= e^2 / 3 for the
// longest edge e (the circumradius of an acute triangle is at most e / sqrt(3); for an obtuse one the maximum
// is (e / 2)^2).
double chord_bound(const CellMeasure& m) { return std::max({m.wu, m.wv, 0.25 * (m.wu + m.wv)}) / 6.0; }

struct Use {
  int face, side;
  bool reversed;
};

struct Cell {
  std::array<Coord, 2> lo, hi;
};

// Disjoint sets over root intervals, so that intervals that meet along a curve get one lattice count.
struct DisjointSets {
  std::vector<int> parent;
  explicit DisjointSets(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(int a, int b) { parent[find(a)] = find(b); }
};

class Tessellator {
public:
  Tessellator(const Brep& brep, const TessellationOptions& opts) : brep_(brep), tol_(opts.chordal_tolerance) {
    require(tol_ > 0 && std::isfinite(tol_), "tessellate: the chordal tolerance must be positive");
    uses_.resize(brep.curves.size());
    for (std::size_t f = 0; f < brep.faces.size(); ++f) {
      const BrepFace& face = brep.faces[f];
      require(face.surface.dim() == 3, [&] { return "tessellate: face " + std::to_string(f) + " is not in 3-D"; });
      for (int s = 0; s < 4; ++s) {
        const int c = face.sides[s].curve;
        require(c >= 0 && c < static_cast<int>(brep.curves.size()), [&] {
          return "tessellate: face " + std::to_string(f) + " side " + std::to_string(s) + " names curve " +
                 std::to_string(c) + " of " + std::to_string(brep.curves.size());
        });
        uses_[c].push_back({static_cast<int>(f), s, face.sides[s].reversed});
      }
    }
    for (std::size_t c = 0; c < brep.curves.size(); ++c)
      for (int v : brep.curves[c].vertices)
        require(v >= 0 && v < brep.num_vertices,
                [&] { return "tessellate: curve " + std::to_string(c) + " names vertex " + std::to_string(v); });
  }

  BrepTessellation run() {
    find_collapsed();
    build_lattices();
    leaves_.resize(brep_.faces.size());
    for (std::size_t f = 0; f < brep_.faces.size(); ++f) {
      const auto& b = breaks_[f];
      for (std::size_t j = 0; j + 1 < b[1].size(); ++j)
        for (std::size_t i = 0; i + 1 < b[0].size(); ++i)
          refine(static_cast<int>(f), Cell{{b[0][i] * kStep, b[1][j] * kStep}, {b[0][i + 1] * kStep, b[1][j + 1] * kStep}});
    }
    balance();
    triangulate();
    return std::move(out_);
  }

private:
  // ---- lattices -------------------------------------------------------------------------------------------

  Vec use_point(const Use& u, double t) const {
    const TensorSpline<2>& s = brep_.faces[u.face].surface;
    return at(s, side_parameters(s, u.side, u.reversed ? 1.0 - t : t));
  }

  // A side shrunk to a point (a pole) is one vertex: its closed curve stays within the tolerance of its start.
  void find_collapsed() {
    collapsed_.assign(brep_.curves.size(), false);
    for (std::size_t c = 0; c < brep_.curves.size(); ++c) {
      if (uses_[c].empty() || brep_.curves[c].vertices[0] != brep_.curves[c].vertices[1]) continue;
      bool collapsed = true;
      for (double x : {0.25, 0.5, 0.75})
        collapsed = collapsed && distance(use_point(uses_[c][0], x), use_point(uses_[c][0], 0)) <= tol_;
      collapsed_[c] = collapsed;
    }
  }

  // Every face direction is cut into root intervals at its knots and at every break of the faces across its
  // sides (repeated until nothing changes, so that faces meeting along a curve cut it at the same places);
  // each root interval is then cut into equal lattice steps, the same number for all intervals that meet along
  // curves, enough for the most curved face among them. Shared curves therefore carry the same lattice on
  // both faces, and cells refined within it put their vertices at the same places on both.
  void build_lattices() {
    const std::size_t nf = brep_.faces.size(), nc = brep_.curves.size();
    std::vector<std::array<std::vector<double>, 2>> fb(nf);
    std::vector<std::vector<double>> cb(nc, std::vector<double>{0.0, 1.0});
    for (std::size_t f = 0; f < nf; ++f) fb[f] = {unit_breaks(brep_.faces[f].surface, 0), unit_breaks(brep_.faces[f].surface, 1)};
    // A closed curve needs three vertices to be a polygon.
    for (std::size_t c = 0; c < nc; ++c)
      if (brep_.curves[c].vertices[0] == brep_.curves[c].vertices[1] && !collapsed_[c]) cb[c] = {0.0, 1.0 / 3, 2.0 / 3, 1.0};
    for (bool changed = true; changed;) {
      changed = false;
      const auto absorb = [&](std::vector<double>& into, const std::vector<double>& from) {
        std::vector<double> m = merged(into, from);
        if (m.size() != into.size()) changed = true;
        into = std::move(m);
      };
      for (std::size_t f = 0; f < nf; ++f)
        for (int s = 0; s < 4; ++s) {
          const FaceSide& fs = brep_.faces[f].sides[s];
          std::vector<double>& face_lines = fb[f][1 - s / 2];
          absorb(cb[fs.curve], fs.reversed ? flipped(face_lines) : face_lines);
          absorb(face_lines, fs.reversed ? flipped(cb[fs.curve]) : cb[fs.curve]);
        }
    }

    // Node ids: (face, direction, interval) then (curve, interval).
    std::vector<std::array<int, 2>> face_node(nf);
    std::vector<int> curve_node(nc);
    int nodes = 0;
    for (std::size_t f = 0; f < nf; ++f)
      for (int k = 0; k < 2; ++k) {
        face_node[f][k] = nodes;
        nodes += static_cast<int>(fb[f][k].size()) - 1;
      }
    for (std::size_t c = 0; c < nc; ++c) {
      curve_node[c] = nodes;
      nodes += static_cast<int>(cb[c].size()) - 1;
    }
    DisjointSets sets(static_cast<std::size_t>(nodes));
    for (std::size_t f = 0; f < nf; ++f)
      for (int s = 0; s < 4; ++s) {
        const FaceSide& fs = brep_.faces[f].sides[s];
        const int m = static_cast<int>(fb[f][1 - s / 2].size()) - 1;
        require(m == static_cast<int>(cb[fs.curve].size()) - 1, [&] {
          return "tessellate: face " + std::to_string(f) + " side " + std::to_string(s) + " does not follow curve " +
                 std::to_string(fs.curve);
        });
        for (int i = 0; i < m; ++i) sets.unite(face_node[f][1 - s / 2] + i, curve_node[fs.curve] + (fs.reversed ? m - 1 - i : i));
      }

    // Lattice steps each root cell needs: enough for the chordal bound at the cell's curvature, and cells
    // about as long in space as they are wide. Kept in double until the memory they need is accepted.
    std::vector<double> count(static_cast<std::size_t>(nodes), 1.0);
    double cells = 0;
    for (std::size_t f = 0; f < nf; ++f) {
      const TensorSpline<2>& s = brep_.faces[f].surface;
      for (std::size_t j = 0; j + 1 < fb[f][1].size(); ++j)
        for (std::size_t i = 0; i + 1 < fb[f][0].size(); ++i) {
          const CellMeasure m = measure(s, param(s, fb[f][0][i], fb[f][1][j]), param(s, fb[f][0][i + 1], fb[f][1][j + 1]));
          const double cu = std::max(1.0, std::ceil(std::sqrt(m.wu / (6 * tol_)))),
                       cv = std::max(1.0, std::ceil(std::sqrt(m.wv / (6 * tol_))));
          const double h = std::min(m.lu / cu, m.lv / cv);
          const double nu = h > 0 ? std::max(cu, std::round(m.lu / h)) : cu, nv = h > 0 ? std::max(cv, std::round(m.lv / h)) : cv;
          double& a = count[sets.find(face_node[f][0] + static_cast<int>(i))];
          double& b = count[sets.find(face_node[f][1] + static_cast<int>(j))];
          a = std::max(a, nu);
          b = std::max(b, nv);
          cells += nu * nv;
        }
    }
    double lattice = 0;
    for (std::size_t c = 0; c < nc; ++c)
      for (std::size_t j = 0; j + 1 < cb[c].size(); ++j) lattice += count[sets.find(curve_node[c] + static_cast<int>(j))];
    // Four triangles per cell, and the cells that grade the flat faces down from their finely cut edges.
    const double triangles = 4 * (cells + 4 * lattice);
    std::ostringstream what;
    what << "tessellating with chordal tolerance " << tol_ << " (about " << std::llround(triangles) << " triangles)";
    require_memory(triangles * kBytesPerTriangle, what.str());
    // Vertex ids are int.
    require(triangles < 1e9, [&] { return what.str() + " exceeds the limit of 1e9 triangles"; });

    lines_.resize(nf);
    breaks_.resize(nf);
    for (std::size_t f = 0; f < nf; ++f)
      for (int k = 0; k < 2; ++k) {
        const std::vector<double>& b = fb[f][k];
        std::vector<double>& lines = lines_[f][k];
        std::vector<Coord>& breaks = breaks_[f][k];
        breaks = {0};
        for (std::size_t i = 0; i + 1 < b.size(); ++i) {
          const auto n = static_cast<Coord>(count[sets.find(face_node[f][k] + static_cast<int>(i))]);
          for (Coord q = 0; q < n; ++q) lines.push_back(b[i] + (b[i + 1] - b[i]) * static_cast<double>(q) / static_cast<double>(n));
          breaks.push_back(breaks.back() + n);
        }
        lines.push_back(1.0);
      }
  }

  static Param<2> param(const TensorSpline<2>& s, double a, double b) {
    const Box<2> d = s.domain();
    return {d.lo[0] + a * (d.hi[0] - d.lo[0]), d.lo[1] + b * (d.hi[1] - d.lo[1])};
  }

  // Unit parameter of a fixed-point lattice coordinate.
  double unit(int f, int k, Coord x) const {
    const std::vector<double>& l = lines_[f][k];
    const auto i = static_cast<std::size_t>(x >> kFrac);
    if (i + 1 >= l.size()) return l.back();
    return l[i] + static_cast<double>(x & (kStep - 1)) / static_cast<double>(kStep) * (l[i + 1] - l[i]);
  }

  Param<2> param(int f, Coord x, Coord y) const { return param(brep_.faces[f].surface, unit(f, 0, x), unit(f, 1, y)); }

  Coord extent(int f, int k) const { return static_cast<Coord>(lines_[f][k].size() - 1) * kStep; }

  // ---- refinement -----------------------------------------------------------------------------------------

  // Where a cell splits in direction k: at the lattice line nearest its middle, or halfway below one step;
  // none when it is one fixed-point unit wide.
  static Coord split_point(const Cell& c, int k) {
    const Coord w = c.hi[k] - c.lo[k];
    if (w > kStep) return c.lo[k] + (w / kStep / 2) * kStep;
    return w >= 2 ? c.lo[k] + w / 2 : -1;
  }

  // Splits c in the directions marked and refines the parts.
  void split(int f, const Cell& c, std::array<bool, 2> dir) {
    std::array<std::vector<std::pair<Coord, Coord>>, 2> ranges;
    for (int k = 0; k < 2; ++k) {
      const Coord m = dir[k] ? split_point(c, k) : -1;
      if (m < 0)
        ranges[k] = {{c.lo[k], c.hi[k]}};
      else
        ranges[k] = {{c.lo[k], m}, {m, c.hi[k]}};
    }
    for (const auto& [v0, v1] : ranges[1])
      for (const auto& [u0, u1] : ranges[0]) refine(f, Cell{{u0, v0}, {u1, v1}});
  }

  // Splits a cell until the chordal bound holds and it is at most twice as long in space as it is wide.
  void refine(int f, const Cell& c) {
    const CellMeasure m = measure(brep_.faces[f].surface, param(f, c.lo[0], c.lo[1]), param(f, c.hi[0], c.hi[1]));
    std::array<bool, 2> dir{m.lu > 2 * m.lv, m.lv > 2 * m.lu};
    if (chord_bound(m) > tol_) {
      dir[0] = dir[0] || m.wu >= 0.25 * m.wv;
      dir[1] = dir[1] || m.wv >= 0.25 * m.wu;
    }
    for (int k = 0; k < 2; ++k) dir[k] = dir[k] && split_point(c, k) >= 0;
    if (dir[0] || dir[1])
      split(f, c, dir);
    else
      leaves_[f].push_back(c);
  }

  // Lattice points of every face's cell corners, by line: for direction k, (position across k, position along
  // k) pairs sorted, so that the points on a cell side are one binary search away. Face sides take the points
  // of their curve, which holds the corners of all faces along it.
  void collect_points() {
    const std::size_t nf = brep_.faces.size();
    points_.assign(nf, {});
    curve_points_.assign(brep_.curves.size(), {});
    for (std::size_t f = 0; f < nf; ++f) {
      auto& p = points_[f];
      for (const Cell& c : leaves_[f])
        for (Coord y : {c.lo[1], c.hi[1]})
          for (Coord x : {c.lo[0], c.hi[0]}) {
            p[0].push_back({y, x});
            p[1].push_back({x, y});
          }
      for (auto& v : p) {
        std::sort(v.begin(), v.end());
        v.erase(std::unique(v.begin(), v.end()), v.end());
      }
      for (int s = 0; s < 4; ++s) {
        const FaceSide& fs = brep_.faces[f].sides[s];
        const int run = 1 - s / 2;
        const Coord across = s % 2 ? extent(static_cast<int>(f), s / 2) : 0;
        const auto& line = p[run];
        for (auto it = std::lower_bound(line.begin(), line.end(), std::pair<Coord, Coord>{across, 0});
             it != line.end() && it->first == across; ++it)
          curve_points_[fs.curve].push_back(to_curve(static_cast<int>(f), s, it->second));
      }
    }
    for (auto& v : curve_points_) {
      std::sort(v.begin(), v.end());
      v.erase(std::unique(v.begin(), v.end()), v.end());
    }
  }

  // A position along face side s in the face's coordinate, as a position along its curve, and back.
  Coord to_curve(int f, int s, Coord x) const {
    return brep_.faces[f].sides[s].reversed ? extent(f, 1 - s / 2) - x : x;
  }

  // Points strictly inside the segment from `from` to `to` (either order) along direction k of face f at
  // `across` in the other direction, in the order from `from` to `to`.
  void side_points(int f, int k, Coord across, Coord from, Coord to, std::vector<Coord>& out) const {
    out.clear();
    const Coord lo = std::min(from, to), hi = std::max(from, to);
    const int fixed = 1 - k;
    if (across == 0 || across == extent(f, fixed)) {
      const int s = 2 * fixed + (across == 0 ? 0 : 1);
      const std::vector<Coord>& c = curve_points_[brep_.faces[f].sides[s].curve];
      const Coord a = to_curve(f, s, lo), b = to_curve(f, s, hi);
      for (auto it = std::upper_bound(c.begin(), c.end(), std::min(a, b)); it != c.end() && *it < std::max(a, b); ++it)
        out.push_back(to_curve(f, s, *it));
      std::sort(out.begin(), out.end());
    } else {
      const auto& line = points_[f][k];
      for (auto it = std::upper_bound(line.begin(), line.end(), std::pair<Coord, Coord>{across, lo});
           it != line.end() && it->first == across && it->second < hi; ++it)
        out.push_back(it->second);
    }
    if (from > to) std::reverse(out.begin(), out.end());
  }

  // Neighbouring cells (on the same face or across a curve) may be finer along a shared side; a side that
  // meets more than one of their corners, or one outside its middle half, is split, until every cell's fan of
  // triangles stays well shaped.
  void balance() {
    std::vector<Coord> pts;
    for (bool changed = true; changed;) {
      changed = false;
      collect_points();
      for (std::size_t f = 0; f < brep_.faces.size(); ++f) {
        std::vector<Cell> cells = std::move(leaves_[f]);
        leaves_[f].clear();
        for (const Cell& c : cells) {
          std::array<bool, 2> dir{false, false};
          for (int k = 0; k < 2; ++k)
            for (Coord across : {c.lo[1 - k], c.hi[1 - k]}) {
              side_points(static_cast<int>(f), k, across, c.lo[k], c.hi[k], pts);
              const double w = static_cast<double>(c.hi[k] - c.lo[k]);
              const bool central = pts.size() == 1 && std::abs(static_cast<double>(pts[0] - c.lo[k]) / w - 0.5) <= 0.25;
              dir[k] = dir[k] || (!pts.empty() && !central);
            }
          for (int k = 0; k < 2; ++k) dir[k] = dir[k] && split_point(c, k) >= 0;
          if (dir[0] || dir[1]) {
            split(static_cast<int>(f), c, dir);
            changed = true;
          } else {
            leaves_[f].push_back(c);
          }
        }
      }
    }
  }

  // ---- triangles ------------------------------------------------------------------------------------------

  int add_vertex(const Vec& x, int face, const Param<2>& uv) {
    out_.mesh.vertices.push_back(x);
    out_.origins.push_back({face, uv});
    return static_cast<int>(out_.mesh.vertices.size()) - 1;
  }

  // One vertex per curve point, evaluated on the first face along the curve; the curve's end points are the
  // Brep's vertices and a collapsed curve is its vertex.
  void curve_vertices() {
    curve_ids_.assign(brep_.curves.size(), {});
    for (std::size_t c = 0; c < brep_.curves.size(); ++c) {
      const std::vector<Coord>& t = curve_points_[c];
      if (uses_[c].empty()) continue;
      const Use& first = uses_[c].front();
      const auto side_param = [&](const Use& u, Coord x) {
        const Coord y = to_curve(u.face, u.side, x);
        const int run = 1 - u.side / 2;
        const Coord across = u.side % 2 ? extent(u.face, u.side / 2) : 0;
        return run == 0 ? param(u.face, y, across) : param(u.face, across, y);
      };
      std::vector<int>& ids = curve_ids_[c];
      ids.resize(t.size());
      for (std::size_t i = 0; i < t.size(); ++i) {
        const Param<2> uv = side_param(first, t[i]);
        const Vec x = at(brep_.faces[first.face].surface, uv);
        for (const Use& u : uses_[c])
          require(distance(at(brep_.faces[u.face].surface, side_param(u, t[i])), x) <= 100 * tol_, [&] {
            return "tessellate: faces " + std::to_string(first.face) + " and " + std::to_string(u.face) +
                   " do not meet along curve " + std::to_string(c);
          });
        const bool end = i == 0 || i + 1 == t.size();
        if (end || collapsed_[c]) {
          const int v = brep_.curves[c].vertices[i + 1 == t.size() && !collapsed_[c] ? 1 : 0];
          if (out_.origins[v].face < 0) {
            out_.mesh.vertices[v] = x;
            out_.origins[v] = {first.face, uv};
          }
          ids[i] = v;
        } else {
          ids[i] = add_vertex(x, first.face, uv);
        }
      }
    }
  }

  void triangulate() {
    out_.mesh.vertices.assign(static_cast<std::size_t>(brep_.num_vertices), Vec{});
    out_.origins.assign(static_cast<std::size_t>(brep_.num_vertices), VertexOrigin{});
    collect_points();
    curve_vertices();
    std::vector<Coord> pts;
    std::vector<std::pair<Coord, Coord>> loop;
    for (std::size_t fi = 0; fi < brep_.faces.size(); ++fi) {
      const int f = static_cast<int>(fi);
      const BrepFace& face = brep_.faces[f];
      const TensorSpline<2>& s = face.surface;
      const std::array<Coord, 2> ext{extent(f, 0), extent(f, 1)};
      // Vertices of the face's interior points, in the order of points_[f][1] (sorted (u, v)).
      const auto& inner = points_[f][1];
      std::vector<int> inner_ids(inner.size(), -1);
      for (std::size_t i = 0; i < inner.size(); ++i) {
        const auto [x, y] = inner[i];
        if (x > 0 && x < ext[0] && y > 0 && y < ext[1]) {
          const Param<2> uv = param(f, x, y);
          inner_ids[i] = add_vertex(at(s, uv), f, uv);
        }
      }
      const auto vertex = [&](Coord x, Coord y) {
        if (x > 0 && x < ext[0] && y > 0 && y < ext[1])
          return inner_ids[std::lower_bound(inner.begin(), inner.end(), std::pair<Coord, Coord>{x, y}) - inner.begin()];
        const int side = x == 0 ? 0 : x == ext[0] ? 1 : y == 0 ? 2 : 3;
        const int curve = face.sides[side].curve;
        const std::vector<Coord>& t = curve_points_[curve];
        const Coord along = to_curve(f, side, side < 2 ? y : x);
        return curve_ids_[curve][std::lower_bound(t.begin(), t.end(), along) - t.begin()];
      };
      for (const Cell& c : leaves_[f]) {
        // The cell's boundary counter-clockwise in (u, v): v = lo, u = hi, v = hi, u = lo.
        loop.clear();
        const std::array<std::array<Coord, 2>, 4> corner{{{c.lo[0], c.lo[1]}, {c.hi[0], c.lo[1]}, {c.hi[0], c.hi[1]}, {c.lo[0], c.hi[1]}}};
        for (int q = 0; q < 4; ++q) {
          const auto& a = corner[q];
          const auto& b = corner[(q + 1) % 4];
          loop.push_back({a[0], a[1]});
          const int k = a[0] == b[0] ? 1 : 0;  // direction the side runs in
          side_points(f, k, a[1 - k], a[k], b[k], pts);
          for (Coord p : pts) loop.push_back(k == 0 ? std::pair{p, a[1]} : std::pair{a[0], p});
        }
        const Param<2> uv = param(f, (c.lo[0] + c.hi[0]) / 2, (c.lo[1] + c.hi[1]) / 2);
        const int centre = add_vertex(at(s, uv), f, uv);
        for (std::size_t i = 0; i < loop.size(); ++i) {
          const auto& [x0, y0] = loop[i];
          const auto& [x1, y1] = loop[(i + 1) % loop.size()];
          int a = vertex(x0, y0), b = vertex(x1, y1);
          if (a == b) continue;  // along a collapsed side
          if (face.flip) std::swap(a, b);
          out_.mesh.triangles.push_back({centre, a, b});
        }
      }
    }
  }

  const Brep& brep_;
  double tol_;
  std::vector<std::vector<Use>> uses_;
  std::vector<bool> collapsed_;
  std::vector<std::array<std::vector<double>, 2>> lines_;  // per face and direction: unit parameter of each lattice line
  std::vector<std::array<std::vector<Coord>, 2>> breaks_;  // per face and direction: lattice indices of root breaks
  std::vector<std::vector<Cell>> leaves_;
  std::vector<std::array<std::vector<std::pair<Coord, Coord>>, 2>> points_;
  std::vector<std::vector<Coord>> curve_points_;
  std::vector<std::vector<int>> curve_ids_;
  BrepTessellation out_;
};

}  // namespace

BrepTessellation tessellate(const Brep& brep, const TessellationOptions& opts) {
  return Tessellator(brep, opts).run();
}

}  // namespace trivar
