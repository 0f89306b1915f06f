#include "trivar/model/trimmed_interfaces.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "trivar/core/number_format.hpp"
#include "trivar/core/vec3.hpp"
#include "trivar/model/curve_matching.hpp"
#include "trivar/model/point_clusters.hpp"
#include "trivar/model/trimmed_vertices.hpp"
#include "trivar/spline/closest_point.hpp"

namespace trivar {

namespace {

using Point3 = std::array<double, 3>;

// Interior fractions of an edge at which edges are compared.
constexpr std::array<double, 3> kEdgeSamples{0.25, 0.5, 0.75};

// The edge's points at kEdgeSamples of its parameter range: on its 3D curve, or along the first trim curve that
// uses it on its surface when it has none.
std::array<Point3, 3> edge_samples(const TrimmedBoundary& b, int e) {
  std::array<Point3, 3> out;
  const TensorSpline<1>& c = b.edges[static_cast<std::size_t>(e)].curve;
  if (c.num_coefs() > 0) {
    const Box<1> d = c.domain();
    for (std::size_t k = 0; k < out.size(); ++k) c.eval({d.lo[0] + kEdgeSamples[k] * d.extent(0)}, out[k].data());
    return out;
  }
  for (const TrimmedFace& f : b.faces)
    for (const TrimLoop& l : f.loops)
      for (const TrimCurve& t : l.curves) {
        if (t.edge != e) continue;
        const Box<1> d = t.pcurve.domain();
        for (std::size_t k = 0; k < out.size(); ++k) {
          const double s = t.edge_reversed ? 1 - kEdgeSamples[k] : kEdgeSamples[k];
          double uv[2];
          t.pcurve.eval({d.lo[0] + s * d.extent(0)}, uv);
          f.surface.eval({uv[0], uv[1]}, out[k].data());
        }
        return out;
      }
  return out;
}

// The V-curves and V-points of the trimmed cells, their Euler characteristics and defects (r's faces known).
void add_curves_and_points(const VModel& model, TrimmedInterfaces& r) {
  const int n = model.num_cells();
  std::vector<TrimmedVertices> tv(static_cast<std::size_t>(n));
  Box<3> box = Box<3>::empty();
  bool any = false;
  double tol = 0;
  for (int c = 0; c < n; ++c) {
    if (!model.cell(c).is_trimmed()) continue;
    const TrimmedSolid& s = *model.cell(c).trim();
    tv[static_cast<std::size_t>(c)] = trimmed_vertices(s.boundary());
    box.extend(s.bounding_box().lo.data());
    box.extend(s.bounding_box().hi.data());
    any = true;
    for (const TrimmedFace& f : s.boundary().faces) tol = std::max(tol, f.tolerance);
    for (const TrimEdge& e : s.boundary().edges) tol = std::max(tol, e.tolerance);
  }
  r.cell_euler.assign(static_cast<std::size_t>(n), 0);
  r.edge_curve.resize(static_cast<std::size_t>(n));
  r.vertex_point.resize(static_cast<std::size_t>(n));
  if (!any) return;
  r.tolerance = tol = std::max(tol, 1e-6 * box.diagonal());
  const auto defect = [&r](std::string s) {
    if (r.defects.size() < 20) r.defects.push_back(std::move(s));
  };
  // V-points: the cells' vertices merged by position.
  std::vector<Point3> positions;
  std::vector<CellCornerRef> owners;
  for (int c = 0; c < n; ++c)
    for (std::size_t v = 0; v < tv[static_cast<std::size_t>(c)].positions.size(); ++v) {
      positions.push_back(tv[static_cast<std::size_t>(c)].positions[v]);
      owners.push_back({c, static_cast<int>(v)});
    }
  const std::vector<int> cluster = cluster_points(positions, tol);
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const auto p = static_cast<std::size_t>(cluster[i]);
    if (p == r.points.size()) r.points.emplace_back();
    VPoint& vp = r.points[p];
    for (int k = 0; k < 3; ++k) vp.position[k] += positions[i][k];
    vp.corners.push_back(owners[i]);
    auto& vmap = r.vertex_point[static_cast<std::size_t>(owners[i].cell)];
    vmap.resize(tv[static_cast<std::size_t>(owners[i].cell)].positions.size());
    vmap[static_cast<std::size_t>(owners[i].corner)] = cluster[i];
  }
  for (VPoint& p : r.points)
    for (double& x : p.position) x /= static_cast<double>(p.corners.size());
  // The V-surface of each cell face (-1 for a non-conforming face).
  std::vector<std::vector<int>> face_surface(static_cast<std::size_t>(n));
  for (int c = 0; c < n; ++c)
    if (model.cell(c).is_trimmed()) face_surface[static_cast<std::size_t>(c)].assign(model.cell(c).trim()->boundary().faces.size(), -1);
  for (std::size_t s = 0; s < r.surfaces.size(); ++s)
    for (const TrimmedFaceRef& h : r.surfaces[s])
      if (h.cell >= 0) face_surface[static_cast<std::size_t>(h.cell)][static_cast<std::size_t>(h.face)] = static_cast<int>(s);
  // V-curves: edges with the same V-points at their ends and the same interior points.
  std::map<std::pair<int, int>, std::vector<int>> by_points;
  std::vector<std::array<Point3, 3>> curve_samples;
  std::vector<CurveCandidate> candidates;
  for (int c = 0; c < n; ++c) {
    if (!model.cell(c).is_trimmed()) continue;
    const TrimmedBoundary& b = model.cell(c).trim()->boundary();
    const TrimmedVertices& t = tv[static_cast<std::size_t>(c)];
    const auto& vmap = r.vertex_point[static_cast<std::size_t>(c)];
    auto& emap = r.edge_curve[static_cast<std::size_t>(c)];
    emap.assign(b.edges.size(), -1);
    for (std::size_t e = 0; e < b.edges.size(); ++e) {
      if (t.edge_vertices[e][0] < 0) continue;
      const int p0 = vmap[static_cast<std::size_t>(t.edge_vertices[e][0])], p1 = vmap[static_cast<std::size_t>(t.edge_vertices[e][1])];
      const std::array<Point3, 3> samples = edge_samples(b, static_cast<int>(e));
      auto& bucket = by_points[{std::min(p0, p1), std::max(p0, p1)}];
      candidates.clear();
      for (int id : bucket) candidates.push_back({r.curves[static_cast<std::size_t>(id)].points, curve_samples[static_cast<std::size_t>(id)]});
      const CurveMatch m = match_curve(candidates, p0, p1, samples, tol, [&](std::size_t i, const Point3& x) {
        // Differently parametrised: this edge's points on the V-curve's first edge.
        const CellEdgeRef first = r.curves[static_cast<std::size_t>(bucket[i])].cell_edges.front();
        const TensorSpline<1>& curve = model.cell(first.cell).trim()->boundary().edges[static_cast<std::size_t>(first.edge)].curve;
        return curve.num_coefs() > 0 ? closest_point(curve, x.data()).distance : std::numeric_limits<double>::infinity();
      });
      int found = m.candidate < 0 ? -1 : bucket[static_cast<std::size_t>(m.candidate)];
      const bool reversed = m.reversed;
      if (found < 0) {
        found = static_cast<int>(r.curves.size());
        VCurve cv;
        cv.points = {p0, p1};
        r.curves.push_back(std::move(cv));
        curve_samples.push_back(samples);
        bucket.push_back(found);
      }
      VCurve& cv = r.curves[static_cast<std::size_t>(found)];
      cv.cell_edges.push_back({c, static_cast<int>(e), reversed});
      for (int f : t.edge_faces[e])
        if (const int s = face_surface[static_cast<std::size_t>(c)][static_cast<std::size_t>(f)]; s >= 0) cv.surfaces.push_back(s);
      emap[e] = found;
      if (t.edge_faces[e].size() % 2 != 0)
        defect("cell " + std::to_string(c) + ": trimming edge " + std::to_string(e) + " is used by " +
               std::to_string(t.edge_faces[e].size()) + " face loops (a closed boundary uses every edge twice)");
      for (int s = 0; s < 2; ++s) {
        const double d = distance(t.edge_ends[e][static_cast<std::size_t>(s)], r.points[static_cast<std::size_t>(s ? p1 : p0)].position);
        if (d > tol)
          defect("cell " + std::to_string(c) + ": the " + (s ? "end" : "start") + " of trimming edge " + std::to_string(e) + " is " +
                 format_number(d) + " from its V-point " + std::to_string(s ? p1 : p0) + " (tolerance " + format_number(tol) + ")");
      }
    }
    r.cell_euler[static_cast<std::size_t>(c)] = t.euler_characteristic;
  }
  for (std::size_t i = 0; i < r.curves.size(); ++i) {
    VCurve& cv = r.curves[i];
    std::sort(cv.surfaces.begin(), cv.surfaces.end());
    cv.surfaces.erase(std::unique(cv.surfaces.begin(), cv.surfaces.end()), cv.surfaces.end());
    for (int p : cv.points) {
      auto& list = r.points[static_cast<std::size_t>(p)].curves;
      if (list.empty() || list.back() != static_cast<int>(i)) list.push_back(static_cast<int>(i));
    }
  }
  // The model's boundary: its faces, the V-curves on them and those curves' V-points.
  std::vector<char> boundary_point(r.points.size(), 0);
  int faces = 0, edges = 0;
  for (const auto& s : r.surfaces)
    if (s[1].cell < 0)
      faces += 2 - static_cast<int>(model.cell(s[0].cell).trim()->boundary().faces[static_cast<std::size_t>(s[0].face)].loops.size());
  for (const VCurve& cv : r.curves)
    if (std::any_of(cv.surfaces.begin(), cv.surfaces.end(), [&](int s) { return r.surfaces[static_cast<std::size_t>(s)][1].cell < 0; })) {
      ++edges;
      for (int p : cv.points) boundary_point[static_cast<std::size_t>(p)] = 1;
    }
  r.boundary_euler = static_cast<int>(std::count(boundary_point.begin(), boundary_point.end(), 1)) - edges + faces;
}

}  // namespace

std::vector<long> paired_trimming_triangles(const VModel& model, std::vector<long>& first_triangle) {
  // Vertices are merged by their exact coordinates, so matching corners become equal ids.
  std::map<std::array<double, 3>, int> ids;
  struct Tri {
    std::array<int, 3> v;
    int cell;
  };
  std::vector<Tri> tris;
  first_triangle.assign(static_cast<std::size_t>(model.num_cells()) + 1, 0);
  for (int ci = 0; ci < model.num_cells(); ++ci) {
    first_triangle[static_cast<std::size_t>(ci)] = static_cast<long>(tris.size());
    const VCell& c = model.cell(ci);
    if (!c.is_trimmed()) continue;
    const TriangleMesh& m = c.trim()->boundary().mesh;
    std::vector<int> local(m.vertices.size());
    for (std::size_t i = 0; i < m.vertices.size(); ++i)
      local[i] = ids.try_emplace(m.vertices[i], static_cast<int>(ids.size())).first->second;
    for (const auto& t : m.triangles) tris.push_back({{local[t[0]], local[t[1]], local[t[2]]}, ci});
  }
  first_triangle.back() = static_cast<long>(tris.size());
  // A triangle by its corners in rotation-normalised order; the opposite orientation has the last two swapped.
  const auto key = [](std::array<int, 3> v) {
    std::rotate(v.begin(), std::min_element(v.begin(), v.end()), v.end());
    return v;
  };
  std::map<std::array<int, 3>, std::vector<long>> by_key;
  for (std::size_t t = 0; t < tris.size(); ++t) by_key[key(tris[t].v)].push_back(static_cast<long>(t));
  std::vector<long> twin(tris.size(), -1);
  for (std::size_t t = 0; t < tris.size(); ++t) {
    if (twin[t] >= 0) continue;
    const auto& v = tris[t].v;
    const auto it = by_key.find(key({v[0], v[2], v[1]}));
    if (it == by_key.end()) continue;
    for (long o : it->second)
      if (twin[static_cast<std::size_t>(o)] < 0 && tris[static_cast<std::size_t>(o)].cell != tris[t].cell) {
        twin[t] = o;
        twin[static_cast<std::size_t>(o)] = static_cast<long>(t);
        break;
      }
  }
  return twin;
}

TrimmedInterfaces trimmed_interfaces(const VModel& model) {
  std::vector<long> first;
  const std::vector<long> twin = paired_trimming_triangles(model, first);
  const int n = model.num_cells();
  // The cell and face of a global triangle index.
  const auto owner = [&](long t) {
    const int c = static_cast<int>(std::upper_bound(first.begin(), first.end(), t) - first.begin()) - 1;
    const auto& tf = model.cell(c).trim()->boundary().triangle_face;
    return TrimmedFaceRef{c, tf[static_cast<std::size_t>(t - first[static_cast<std::size_t>(c)])]};
  };
  TrimmedInterfaces r;
  r.twin.resize(static_cast<std::size_t>(n));
  r.neighbours.resize(static_cast<std::size_t>(n));
  for (int c = 0; c < n; ++c) {
    if (!model.cell(c).is_trimmed()) continue;
    const TrimmedBoundary& b = model.cell(c).trim()->boundary();
    // Per face: the one face its paired triangles lie on ({-2, -2} once they lie on several), and whether some
    // triangle of it is unpaired.
    std::vector<TrimmedFaceRef> other(b.faces.size());
    std::vector<char> paired(b.faces.size(), 0), unpaired(b.faces.size(), 0);
    for (std::size_t t = 0; t < b.triangle_face.size(); ++t) {
      const auto f = static_cast<std::size_t>(b.triangle_face[t]);
      const long o = twin[static_cast<std::size_t>(first[static_cast<std::size_t>(c)]) + t];
      if (o < 0) {
        unpaired[f] = 1;
        continue;
      }
      const TrimmedFaceRef of = owner(o);
      if (!paired[f]) other[f] = of;
      else if (!(other[f] == of)) other[f] = {-2, -2};
      paired[f] = 1;
    }
    r.twin[static_cast<std::size_t>(c)].assign(b.faces.size(), {});
    for (std::size_t f = 0; f < b.faces.size(); ++f) {
      const TrimmedFaceRef self{c, static_cast<int>(f)};
      if (!paired[f]) {
        r.surfaces.push_back({self, {}});
        ++r.boundary;
      } else if (unpaired[f] || other[f].cell < 0) {
        r.non_conforming.push_back(self);
      } else {
        r.twin[static_cast<std::size_t>(c)][f] = other[f];
      }
    }
  }
  // A pair counts as shared when each side names the other (the twin's own triangles may be partly unpaired).
  for (int c = 0; c < n; ++c)
    for (std::size_t f = 0; f < r.twin[static_cast<std::size_t>(c)].size(); ++f) {
      TrimmedFaceRef& o = r.twin[static_cast<std::size_t>(c)][f];
      if (o.cell < 0) continue;
      const auto& back = r.twin[static_cast<std::size_t>(o.cell)];
      if (!(back[static_cast<std::size_t>(o.face)] == TrimmedFaceRef{c, static_cast<int>(f)})) {
        r.non_conforming.push_back({c, static_cast<int>(f)});
        o = {};
        continue;
      }
      r.neighbours[static_cast<std::size_t>(c)].push_back(o.cell);
      if (c < o.cell) {
        r.surfaces.push_back({TrimmedFaceRef{c, static_cast<int>(f)}, o});
        ++r.shared;
      }
    }
  // Boundary V-surfaces after the shared ones.
  std::stable_partition(r.surfaces.begin(), r.surfaces.end(), [](const auto& s) { return s[1].cell >= 0; });
  for (auto& nb : r.neighbours) {
    std::sort(nb.begin(), nb.end());
    nb.erase(std::unique(nb.begin(), nb.end()), nb.end());
  }
  add_curves_and_points(model, r);
  return r;
}

}  // namespace trivar
