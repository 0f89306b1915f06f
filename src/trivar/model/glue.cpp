#include "trivar/model/glue.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "trivar/core/error.hpp"
#include "trivar/core/number_format.hpp"
#include "trivar/core/tolerance.hpp"
#include "trivar/core/vec3.hpp"
#include "trivar/model/curve_matching.hpp"
#include "trivar/model/point_clusters.hpp"
#include "trivar/spline/closest_point.hpp"
#include "trivar/spline/iso_extraction.hpp"
#include "trivar/spline/measure.hpp"
#include "trivar/spline/reparametrization.hpp"

namespace trivar {

std::string NonConformingFace::describe() const {
  return "cell " + std::to_string(cell_a) + " face " + std::to_string(face_a) + " and cell " +
         std::to_string(cell_b) + " face " + std::to_string(face_b) + ": " +
         (reason == Reason::control_nets_differ ? "coincident, control nets differ" : "partial overlap");
}

std::vector<int> VTopology::cells_around_curve(int curve) const {
  std::vector<int> cells;
  for (const auto& e : curves.at(static_cast<std::size_t>(curve)).cell_edges) cells.push_back(e.cell);
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  return cells;
}

namespace {

// Largest tolerance relative to the bounding-box diagonal of the model.
constexpr double kMaxRelativeTolerance = 1e-3;

double dist(const double* a, const double* b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

Param<3> corner_param(const Box<3>& dom, int corner) {
  Param<3> u;
  for (int k = 0; k < 3; ++k) u[k] = (corner >> k) & 1 ? dom.hi[k] : dom.lo[k];
  return u;
}

// The cell edge as a curve: fix the two other directions, the higher one first so the lower keeps its index.
TensorSpline<1> edge_curve(const TensorSpline<3>& g, int edge) {
  const int e = edge_direction(edge);
  const int o1 = e == 0 ? 1 : 0, o2 = e == 2 ? 1 : 2;
  const Param<3> c = corner_param(g.domain(), edge_corners(edge)[0]);
  return iso_extract(iso_extract(g, o2, c[o2]), o1, c[o1]);
}

// The face surface b re-expressed in the parameters of face surface a, given the orientation a -> b.
TensorSpline<2> align(const TensorSpline<2>& b, const FaceOrientation& o, const Box<2>& a_domain) {
  TensorSpline<2> r = b;
  if (o.flip_s) r = reverse(r, 0);
  if (o.flip_t) r = reverse(r, 1);
  if (o.swap) r = swap_directions(r, 0, 1);
  for (int k = 0; k < 2; ++k) r = reparametrize(r, k, a_domain.lo[k], a_domain.hi[k]);
  return r;
}

bool same_net(const TensorSpline<2>& a, const TensorSpline<2>& b, double tol) {
  if (a.is_rational() != b.is_rational()) return false;
  for (int k = 0; k < 2; ++k) {
    const auto& ka = a.knots(k).knots();
    const auto& kb = b.knots(k).knots();
    if (a.degree(k) != b.degree(k) || ka.size() != kb.size()) return false;
    const double len = a.knots(k).end() - a.knots(k).start();
    for (std::size_t i = 0; i < ka.size(); ++i)
      if (std::abs(ka[i] - kb[i]) > tol::knot * len) return false;
  }
  for (int i = 0; i < a.num_coefs(); ++i) {
    double pa[3], pb[3];
    a.control_point(i, pa);
    b.control_point(i, pb);
    if (dist(pa, pb) > tol) return false;
    if (std::abs(a.weight(i) - b.weight(i)) > 1e-9 * std::max(a.weight(i), b.weight(i))) return false;
  }
  return true;
}

Param<2> face_param(const Box<2>& dom, double s, double t) {
  return {dom.lo[0] + s * dom.extent(0), dom.lo[1] + t * dom.extent(1)};
}

// Largest distance between a and b at equal parameters over an n x n grid (b's domain is a's after align()).
double param_gap(const TensorSpline<2>& a, const TensorSpline<2>& b, int n) {
  const Box<2> dom = a.domain();
  double gap = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Param<2> st = face_param(dom, i / (n - 1.0), j / (n - 1.0));
      double pa[3], pb[3];
      a.eval(st, pa);
      b.eval(st, pb);
      gap = std::max(gap, dist(pa, pb));
    }
  return gap;
}

// Every point of the n x n grid of a within tol of surface b (all of them, or at least one when `any`). With
// `interior`, the grid is interior to a and only foot points interior to b count.
bool samples_on(const TensorSpline<2>& a, const TensorSpline<2>& b, int n, double tol, bool interior, bool any) {
  const Box<2> dom = a.domain();
  double lo[3], hi[3];
  b.control_bounds(lo, hi);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Param<2> st = interior ? face_param(dom, (i + 0.5) / n, (j + 0.5) / n)
                                   : face_param(dom, i / (n - 1.0), j / (n - 1.0));
      double p[3];
      a.eval(st, p);
      bool on = true;
      for (int k = 0; k < 3; ++k) on = on && p[k] >= lo[k] - tol && p[k] <= hi[k] + tol;
      if (on) {
        // For the overlap test the foot point must be inside b too: a sample on b's rim is edge contact.
        const ClosestPoint<2> cp = closest_point(b, p);
        on = cp.distance <= tol;
        const Box<2> bd = b.domain();
        for (int k = 0; k < 2 && interior; ++k)
          on = on && std::min(cp.param[k] - bd.lo[k], bd.hi[k] - cp.param[k]) > 1e-9 * bd.extent(k);
      }
      if (on && any) return true;
      if (!on && !any) return false;
    }
  return !any;
}

bool collapsed_face(const TensorSpline<2>& f, double tol) {
  const int ns = f.count(0), nt = f.count(1);
  bool along_s = true, along_t = true;
  double p[3], q[3];
  for (int j = 0; j < nt; ++j) {
    f.control_point(ns * j, p);
    for (int i = 1; i < ns; ++i) {
      f.control_point(i + ns * j, q);
      along_s = along_s && dist(p, q) <= tol;
    }
  }
  for (int i = 0; i < ns; ++i) {
    f.control_point(i, p);
    for (int j = 1; j < nt; ++j) {
      f.control_point(i + ns * j, q);
      along_t = along_t && dist(p, q) <= tol;
    }
  }
  return along_s || along_t;
}

// Zero volume up to the tolerance: the cell's volume is at most tol times the area of the largest side of its
// bounding box, so it is thinner than the tolerance somewhere across its whole extent.
void require_solid(const TensorSpline<3>& g, int cell, double tol) {
  Box<3> b;
  g.control_bounds(b.lo.data(), b.hi.data());
  std::array<double, 3> e{b.extent(0), b.extent(1), b.extent(2)};
  std::sort(e.begin(), e.end());
  const double volume = measure(g, 2, 1);
  require(volume > tol * e[1] * e[2], [&] {
    return "glue: cell " + std::to_string(cell) + " is collapsed: volume " + format_number(volume) +
           " is no more than the tolerance " + format_number(tol) + " times its extent " + format_number(e[1]) +
           " x " + format_number(e[2]);
  });
}

}  // namespace

VTopology glue(std::span<const VCell> cells, const GlueOptions& options) {
  require(options.samples >= 2, "glue: samples must be at least 2, got " + std::to_string(options.samples));
  require(options.relative_tolerance > 0 || options.absolute_tolerance > 0, "glue: the tolerance must be positive");
  const int nc = static_cast<int>(cells.size());
  const int ns = options.samples;
  VTopology topo;

  Box<3> box = Box<3>::empty();
  for (const auto& c : cells) {
    double lo[3], hi[3];
    c.geometry().control_bounds(lo, hi);
    box.extend(lo);
    box.extend(hi);
  }
  const double tol = options.absolute_tolerance > 0 ? options.absolute_tolerance
                                                    : options.relative_tolerance * (nc ? box.diagonal() : 1.0);
  // A tolerance near the model's size merges the corners of a cell and leaves no boundary at all.
  require(nc == 0 || tol <= kMaxRelativeTolerance * box.diagonal(), [&] {
    const std::string given = options.absolute_tolerance > 0
                                  ? "absolute tolerance " + format_number(options.absolute_tolerance)
                                  : "relative tolerance " + format_number(options.relative_tolerance);
    return "glue: " + given + " is larger than " + format_number(kMaxRelativeTolerance) +
           " of the model's size (bounding-box diagonal " + format_number(box.diagonal()) + ")";
  });
  require(std::isfinite(tol) && tol > 0, "glue: the model has zero extent");
  topo.tolerance = tol;
  for (int c = 0; c < nc; ++c) require_solid(cells[c].geometry(), c, tol);

  // 1. V-points.
  std::vector<Vec3> corner_pos(static_cast<std::size_t>(8 * nc));
  for (int c = 0; c < nc; ++c)
    for (int k = 0; k < 8; ++k)
      cells[c].geometry().eval(corner_param(cells[c].geometry().domain(), k), corner_pos[8 * c + k].data());
  {
    const std::vector<int> id = cluster_points(corner_pos, tol);
    topo.cell_corners.resize(static_cast<std::size_t>(nc));
    for (int i = 0; i < 8 * nc; ++i) {
      const int r = id[static_cast<std::size_t>(i)];
      if (r == static_cast<int>(topo.points.size())) topo.points.push_back({corner_pos[i], {}, {}});
      topo.cell_corners[i / 8][i % 8] = r;
      topo.points[r].corners.push_back({i / 8, i % 8});
    }
  }

  // 2. V-curves. Samples at interior fractions k / (ns + 1) of each cell edge.
  std::vector<std::vector<Vec3>> edge_samples(static_cast<std::size_t>(12 * nc));
  for (int c = 0; c < nc; ++c) {
    const auto& g = cells[c].geometry();
    const Box<3> dom = g.domain();
    for (int e = 0; e < 12; ++e) {
      auto& s = edge_samples[12 * c + e];
      s.resize(static_cast<std::size_t>(ns));
      Param<3> u = corner_param(dom, edge_corners(e)[0]);
      const int d = edge_direction(e);
      for (int k = 0; k < ns; ++k) {
        u[d] = dom.lo[d] + (k + 1.0) / (ns + 1) * dom.extent(d);
        g.eval(u, s[k].data());
      }
    }
  }
  topo.cell_edges.resize(static_cast<std::size_t>(nc));
  std::map<std::pair<int, int>, std::vector<int>> curves_by_points;
  std::vector<CurveCandidate> candidates;
  for (int c = 0; c < nc; ++c)
    for (int e = 0; e < 12; ++e) {
      const auto [c0, c1] = edge_corners(e);
      const int p0 = topo.cell_corners[c][c0], p1 = topo.cell_corners[c][c1];
      const auto& s = edge_samples[12 * c + e];
      auto& bucket = curves_by_points[{std::min(p0, p1), std::max(p0, p1)}];
      candidates.clear();
      for (int id : bucket) {
        const CellEdgeRef rep = topo.curves[id].cell_edges.front();
        candidates.push_back({topo.curves[id].points, edge_samples[12 * rep.cell + rep.edge]});
      }
      const CurveMatch m = match_curve(candidates, p0, p1, s, tol, [&](std::size_t i, const Vec3& x) {
        const CellEdgeRef rep = topo.curves[bucket[i]].cell_edges.front();
        return closest_point(edge_curve(cells[rep.cell].geometry(), rep.edge), x.data()).distance;
      });
      int found = m.candidate < 0 ? -1 : bucket[static_cast<std::size_t>(m.candidate)];
      if (found < 0) {
        found = static_cast<int>(topo.curves.size());
        VCurve cv;
        cv.points = {p0, p1};
        bool at_point = p0 == p1;
        for (int k = 0; k < ns && at_point; ++k) at_point = distance(s[k], topo.points[p0].position) <= tol;
        cv.degenerate = at_point;
        topo.curves.push_back(std::move(cv));
        bucket.push_back(found);
      }
      topo.curves[found].cell_edges.push_back({c, e, m.reversed});
      topo.cell_edges[c][e] = found;
    }

  // 3. Shared faces.
  std::vector<std::array<TensorSpline<2>, 6>> faces;
  faces.reserve(static_cast<std::size_t>(nc));
  for (const auto& c : cells) faces.push_back(boundary_faces(c.geometry()));
  topo.halves.resize(static_cast<std::size_t>(6 * nc));
  std::map<std::array<int, 4>, std::vector<int>> halves_by_points;
  for (int c = 0; c < nc; ++c)
    for (int f = 0; f < 6; ++f) {
      HalfVSurface& h = topo.halves[6 * c + f];
      h.cell = c, h.face = f;
      h.degenerate = collapsed_face(faces[c][f], tol);
      // A trimmed cell's box faces are not its boundary (its trimming faces are), so they are never shared.
      if (h.degenerate || cells[c].is_trimmed()) continue;
      std::array<int, 4> key;
      for (int k = 0; k < 4; ++k) key[k] = topo.cell_corners[c][face_corner(f, k & 1, k >> 1)];
      std::sort(key.begin(), key.end());
      halves_by_points[key].push_back(6 * c + f);
    }
  auto corner_ids = [&](int h) {
    std::array<int, 4> ids;
    for (int k = 0; k < 4; ++k) ids[k] = topo.cell_corners[h / 6][face_corner(h % 6, k & 1, k >> 1)];
    return ids;
  };
  for (auto& [key, list] : halves_by_points) {
    for (std::size_t ia = 0; ia < list.size(); ++ia) {
      const int ha = list[ia];
      if (topo.halves[ha].twin >= 0) continue;
      for (std::size_t ib = ia + 1; ib < list.size() && topo.halves[ha].twin < 0; ++ib) {
        const int hb = list[ib];
        if (topo.halves[hb].twin >= 0) continue;
        const TensorSpline<2>& A = faces[ha / 6][ha % 6];
        const TensorSpline<2>& B = faces[hb / 6][hb % 6];
        const auto ida = corner_ids(ha), idb = corner_ids(hb);
        // Best match over the corner-consistent orientations: 0 none, 1 on B by closest point, 2 equal at
        // aligned parameters, 3 equal control nets.
        int best = 0;
        FaceOrientation best_o;
        for (int code = 0; code < 8 && best < 3; ++code) {
          const FaceOrientation o = FaceOrientation::from_code(code);
          bool corners = true;
          for (int k = 0; k < 4 && corners; ++k) {
            const Param<2> m = o.map({static_cast<double>(k & 1), static_cast<double>(k >> 1)});
            corners = ida[k] == idb[static_cast<int>(m[0]) + 2 * static_cast<int>(m[1])];
          }
          if (!corners) continue;
          const TensorSpline<2> R = align(B, o, A.domain());
          int score = same_net(A, R, tol) ? 3 : param_gap(A, R, ns) <= tol ? 2 : 0;
          if (score == 0 && best == 0 && samples_on(A, B, ns, tol, false, false) && samples_on(B, A, ns, tol, false, false))
            score = 1;
          if (score > best) best = score, best_o = o;
        }
        if (best == 0) continue;
        topo.halves[ha].twin = hb, topo.halves[ha].to_twin = best_o;
        topo.halves[hb].twin = ha, topo.halves[hb].to_twin = best_o.inverse();
        if (best < 3)
          topo.non_conforming.push_back({ha / 6, ha % 6, hb / 6, hb % 6, NonConformingFace::Reason::control_nets_differ});
      }
    }
  }

  // A face left over in a group whose other faces are paired, and that coincides with one of them, belongs to a
  // third cell: the model overlaps itself there.
  for (const auto& [key, list] : halves_by_points) {
    if (list.size() < 3) continue;
    for (int h : list) {
      if (topo.halves[h].twin >= 0) continue;
      for (int g : list) {
        if (topo.halves[g].twin < 0) continue;
        const TensorSpline<2>& A = faces[h / 6][h % 6];
        const TensorSpline<2>& B = faces[g / 6][g % 6];
        require(!(samples_on(A, B, ns, tol, false, false) && samples_on(B, A, ns, tol, false, false)), [&] {
          return "glue: face " + std::to_string(h % 6) + " of cell " + std::to_string(h / 6) +
                 " coincides with the face shared by cells " + std::to_string(g / 6) + " and " +
                 std::to_string(topo.halves[g].twin / 6) + ": a face of more than two cells";
        });
      }
    }
  }
  // Two cells whose faces are all glued to each other enclose the same volume twice.
  for (int c = 0; c < nc; ++c) {
    int other = -1;
    bool all = true;
    for (int f = 0; f < 6 && all; ++f) {
      const HalfVSurface& h = topo.halves[6 * c + f];
      if (h.degenerate) continue;
      all = h.twin >= 0 && h.twin / 6 != c && (other < 0 || h.twin / 6 == other);
      other = h.twin / 6;
    }
    require(!all || other < 0, [&] {
      return "glue: cells " + std::to_string(std::min(c, other)) + " and " + std::to_string(std::max(c, other)) +
             " coincide (every face of one is glued to the other)";
    });
  }

  // 4. Partial overlaps between the remaining boundary faces of different cells.
  {
    std::vector<int> open;
    std::vector<Box<3>> bounds;
    for (int h = 0; h < 6 * nc; ++h)
      if (!topo.halves[h].degenerate && topo.halves[h].twin < 0 && !cells[h / 6].is_trimmed()) {
        open.push_back(h);
        Box<3> b;
        faces[h / 6][h % 6].control_bounds(b.lo.data(), b.hi.data());
        bounds.push_back(b);
      }
    for (std::size_t i = 0; i < open.size(); ++i)
      for (std::size_t j = i + 1; j < open.size(); ++j) {
        const int ha = open[i], hb = open[j];
        if (ha / 6 == hb / 6) continue;
        bool touch = true;
        for (int k = 0; k < 3; ++k)
          touch = touch && bounds[i].lo[k] <= bounds[j].hi[k] + tol && bounds[j].lo[k] <= bounds[i].hi[k] + tol;
        if (!touch) continue;
        const auto& A = faces[ha / 6][ha % 6];
        const auto& B = faces[hb / 6][hb % 6];
        if (samples_on(A, B, ns, tol, true, true) || samples_on(B, A, ns, tol, true, true))
          topo.non_conforming.push_back({ha / 6, ha % 6, hb / 6, hb % 6, NonConformingFace::Reason::partial_overlap});
      }
  }

  // 5. V-surfaces and the incidence lists.
  for (int h = 0; h < 6 * nc; ++h) {
    HalfVSurface& half = topo.halves[h];
    if (half.degenerate || half.surface >= 0) continue;
    VSurface s;
    s.halves = {h, half.twin};
    for (int k = 0; k < 4; ++k) s.curves[k] = topo.cell_edges[half.cell][face_edge(half.face, k)];
    const int id = static_cast<int>(topo.surfaces.size());
    half.surface = id;
    if (half.twin >= 0) topo.halves[half.twin].surface = id;
    topo.surfaces.push_back(s);
  }
  for (const auto& nf : topo.non_conforming)
    if (nf.reason == NonConformingFace::Reason::control_nets_differ)
      topo.surfaces[topo.halves[6 * nf.cell_a + nf.face_a].surface].conforming = false;
  for (int s = 0; s < static_cast<int>(topo.surfaces.size()); ++s)
    for (int c : topo.surfaces[s].curves) {
      auto& list = topo.curves[c].surfaces;
      if (list.empty() || list.back() != s) list.push_back(s);
    }
  for (int c = 0; c < static_cast<int>(topo.curves.size()); ++c) {
    for (int p : topo.curves[c].points) {
      auto& list = topo.points[p].curves;
      if (list.empty() || list.back() != c) list.push_back(c);
    }
  }
  return topo;
}

}  // namespace trivar
