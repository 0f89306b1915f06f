#include "trivar/iga/trimmed_space.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include "trivar/core/error.hpp"
#include "trivar/core/parallel.hpp"
#include "trivar/lr/lr_spline.hpp"

namespace trivar {

namespace {

// Whether every vertex of the triangle lies in the plane x_k = c, to within tol.
bool in_plane(const TriangleMesh& m, const std::array<int, 3>& tri, int k, double c, double tol) {
  for (int v : tri)
    if (std::abs(m.vertices[static_cast<std::size_t>(v)][k] - c) > tol) return false;
  return true;
}

// Whether the open boxes overlap.
bool boxes_overlap(const Box<3>& a, const Box<3>& b) {
  for (int k = 0; k < 3; ++k)
    if (a.hi[k] <= b.lo[k] || b.hi[k] <= a.lo[k]) return false;
  return true;
}

// How far a mesh vertex of a plane face may lie from its plane: rounding, or the geometric tolerance of the
// boundary's edges and faces (a Boolean of trimmed operands rebuilds their edge curves by approximation, and
// the mesh vertices on those edges follow the curves, 1e-7 off the planes they bound).
double plane_tolerance(const TrimmedBoundary& b, double diagonal) {
  double tol = 1e-12 * diagonal;
  for (const TrimEdge& e : b.edges) tol = std::max(tol, e.tolerance);
  for (const TrimmedFace& f : b.faces) tol = std::max(tol, f.tolerance);
  return tol;
}

}  // namespace

TensorSpline<3> identity_geometry(const Box<3>& box, int degree, int elements) {
  std::array<KnotVector, 3> knots;
  std::array<std::vector<double>, 3> g;
  for (int k = 0; k < 3; ++k) {
    knots[k] = KnotVector::open_uniform(degree, elements, box.lo[k], box.hi[k]);
    g[k] = knots[k].greville();
  }
  std::vector<double> coefs;
  for (std::size_t c = 0; c < g[2].size(); ++c)
    for (std::size_t b = 0; b < g[1].size(); ++b)
      for (std::size_t a = 0; a < g[0].size(); ++a) coefs.insert(coefs.end(), {g[0][a], g[1][b], g[2][c]});
  return TensorSpline<3>(knots, 3, false, std::move(coefs));
}

Box<3> analysis_box(const TrimmedSolid& solid) {
  const TrimmedBoundary& b = solid.boundary();
  Box<3> box = Box<3>::empty();
  for (const auto& v : b.mesh.vertices) box.extend(v.data());
  const double tol = plane_tolerance(b, box.diagonal());
  for (int k = 0; k < 3; ++k)
    for (int side = 0; side < 2; ++side) {
      double& c = side == 0 ? box.lo[k] : box.hi[k];
      const bool flat = std::any_of(b.mesh.triangles.begin(), b.mesh.triangles.end(),
                                    [&](const std::array<int, 3>& t) { return in_plane(b.mesh, t, k, c, tol); });
      if (!flat) c += side == 0 ? -b.chordal_tolerance : b.chordal_tolerance;
    }
  return box;
}

namespace {

// Per face and side (2 * dir + side): whether every triangle of the face lies in that side plane of the box.
std::vector<std::array<char, 6>> faces_in_side_planes(const TrimmedSolid& solid, const Box<3>& box) {
  const TrimmedBoundary& b = solid.boundary();
  const double tol = plane_tolerance(b, box.diagonal());
  std::vector<std::array<char, 6>> on(b.faces.size(), {1, 1, 1, 1, 1, 1});
  for (std::size_t t = 0; t < b.mesh.triangles.size(); ++t)
    for (int s = 0; s < 6; ++s) {
      char& o = on[static_cast<std::size_t>(b.triangle_face[t])][static_cast<std::size_t>(s)];
      o = o && in_plane(b.mesh, b.mesh.triangles[t], s / 2, s % 2 == 0 ? box.lo[s / 2] : box.hi[s / 2], tol);
    }
  return on;
}

}  // namespace

std::vector<int> faces_on_box_sides(const TrimmedSolid& solid, const Box<3>& box) {
  const auto on = faces_in_side_planes(solid, box);
  std::vector<int> faces;
  for (std::size_t f = 0; f < on.size(); ++f)
    if (std::any_of(on[f].begin(), on[f].end(), [](char c) { return c != 0; })) faces.push_back(static_cast<int>(f));
  return faces;
}

std::vector<Face> box_sides_with_faces(const TrimmedSolid& solid, const Box<3>& box) {
  const auto on = faces_in_side_planes(solid, box);
  std::vector<Face> sides;
  for (int s = 0; s < 6; ++s)
    if (std::any_of(on.begin(), on.end(), [s](const std::array<char, 6>& f) { return f[static_cast<std::size_t>(s)] != 0; }))
      sides.push_back({s / 2, s % 2, 0});
  return sides;
}

RefinedSpace<3> trimmed_space(const TrimmedSolid& solid, const Box<3>& box, int degree, int elements, int threads,
                              const TrimmedSpaceOptions& opts) {
  std::vector<char> skip(solid.boundary().faces.size(), 0);
  for (int f : faces_on_box_sides(solid, box)) skip[static_cast<std::size_t>(f)] = 1;
  return trimmed_space({TrimmedPart{&solid, std::move(skip)}}, box, degree, elements, threads, opts);
}

RefinedSpace<3> trimmed_space(const std::vector<TrimmedPart>& parts, const Box<3>& box, int degree, int elements,
                              int threads, const TrimmedSpaceOptions& opts, std::vector<std::vector<int>>* element_parts) {
  require(degree >= 1 && elements >= 1, "trimmed space: the degree and the elements per direction must be at least 1");
  require(opts.extra_points >= 0 && opts.depth >= 0, "trimmed space: extra points and depth must not be negative");
  require(!parts.empty(), "trimmed space: no trimmed solid");
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const TrimmedSolid& solid = *parts[i].solid;
    const Box<3>& sb = solid.bounding_box();
    const double slack = 1e-9 * box.diagonal() + solid.boundary().chordal_tolerance;
    for (int k = 0; k < 3; ++k)
      require(sb.lo[k] >= box.lo[k] - slack && sb.hi[k] <= box.hi[k] + slack, [&] {
        return "trimmed space: the box does not hold " + (parts.size() > 1 ? "solid " + std::to_string(i) : std::string("the solid")) +
               " in direction " + std::to_string(k);
      });
  }
  const LRSpline<3> lr(identity_geometry(box, degree, elements));
  RefinedSpace<3> s = refined_space(lr, threads);
  // The LR locator refers to the spline, which ends here: elements are found on the uniform grid instead.
  const int n = elements;
  auto cell = [n, box](const Param<3>& u, int k) {
    return std::clamp(static_cast<int>((u[k] - box.lo[k]) / box.extent(k) * n), 0, n - 1);
  };
  auto index = std::make_shared<std::vector<int>>(static_cast<std::size_t>(n) * n * n, -1);
  for (std::size_t e = 0; e < s.elements.size(); ++e) {
    const auto c = s.elements[e].box.center();
    (*index)[(static_cast<std::size_t>(cell(c, 2)) * n + cell(c, 1)) * n + cell(c, 0)] = static_cast<int>(e);
  }
  s.locate = [index, cell, n](const Param<3>& u) {
    return (*index)[(static_cast<std::size_t>(cell(u, 2)) * n + cell(u, 1)) * n + cell(u, 0)];
  };

  const TrimmedQuadratureOptions q{degree + 1 + opts.extra_points, opts.depth};
  if (element_parts) element_parts->assign(s.elements.size(), {});
  parallel_for(static_cast<std::ptrdiff_t>(s.elements.size()), threads, [&](std::ptrdiff_t e) {
    RefinedElement<3>& el = s.elements[static_cast<std::size_t>(e)];
    std::vector<VolumePoint> vol;
    std::vector<SurfacePoint> surf;
    std::vector<int> holding;
    bool inside = false;
    for (std::size_t i = 0; i < parts.size() && !inside; ++i) {
      if (!boxes_overlap(parts[i].solid->bounding_box(), el.box)) continue;
      const std::size_t v0 = vol.size(), s0 = surf.size();
      const BoxPlacement p = trimmed_box_quadrature(*parts[i].solid, el.box, q, vol, &surf, parts[i].skip_faces);
      if (p == BoxPlacement::inside) {
        // Wholly inside one part (the others, which cannot overlap it, at most graze it within their
        // tolerance): the Gauss rule.
        inside = true;
        holding = {static_cast<int>(i)};
      } else if (vol.size() > v0 || surf.size() > s0) {
        holding.push_back(static_cast<int>(i));
      }
    }
    if (inside) {
      vol.clear();
      surf.clear();
    }
    // An element's empty rule means its whole box: a cut element without inside points (the boundary only grazes
    // it, or a part's faces pass through where another part's volume was not found) is outside, with its few
    // boundary points, rather than wholly inside.
    el.outside = !inside && vol.empty();
    if (el.outside) {
      surf.clear();
      holding.clear();
    }
    for (const VolumePoint& v : vol) el.rule.push_back({v.x, v.weight});
    for (const SurfacePoint& sp : surf) el.trim_sides.push_back({sp.x, sp.normal, sp.weight});
    if (element_parts) (*element_parts)[static_cast<std::size_t>(e)] = std::move(holding);
  });
  require(std::any_of(s.elements.begin(), s.elements.end(), [](const RefinedElement<3>& e) { return !e.outside; }),
          "trimmed space: no element of the box meets the solid");
  return s;
}

}  // namespace trivar
