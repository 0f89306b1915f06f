#include "trivar/iga/t_mesh_space.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>
#include <string>

#include "trivar/core/error.hpp"
#include "trivar/iga/conforming_split.hpp"
#include "trivar/spline/knot_insertion.hpp"
#include "trivar/tspline/t_mesh_patches.hpp"

namespace trivar {

namespace {

// The patches cut to conform and refined, identified across shared sides (by their control points in the
// space of `dim` coordinates: 2 planar, 3 a surface), with the surfaces (dim 3) refined like the spaces.
TMeshSurfaceSpace build_t_mesh_space(const TMeshSurface& surface, int subdivisions, TMeshSpaceReport* report, bool planar) {
  require(subdivisions >= 1, "T-mesh space: subdivisions must be at least 1, got " + std::to_string(subdivisions));
  TMeshPatchOptions po;
  po.levels = 0;
  const TMeshPatches patches = t_mesh_patches(surface, po);
  Box<3> box = Box<3>::empty();
  for (const RationalPoint& p : surface.mesh().points) box.extend(p.xyz.data());
  const double size = box.diagonal();
  require(!planar || box.extent(2) <= 1e-12 * size, [&] {
    return "T-mesh space: the control points span " + std::to_string(box.extent(2)) + " in z; analysis needs a planar mesh (z constant)";
  });
  // Faces crossed by T-junction extensions are several Bezier elements and T-junctions put corners inside sides:
  // the pieces are cut until their sides conform.
  const auto keep = [](const TensorSpline<2>& s, int d) {
    std::vector<double> c;
    for (int i = 0; i < s.num_coefs(); ++i) {
      const double* q = s.coef(i);
      c.insert(c.end(), q, q + d);
      if (s.is_rational()) c.push_back(q[3]);
    }
    return TensorSpline<2>(s.knot_vectors(), d, s.is_rational(), std::move(c));
  };
  std::vector<TensorSpline<2>> pieces_in;
  for (const FacePatch& f : patches.patches) pieces_in.push_back(planar ? keep(f.surface, 2) : f.surface);
  ConformingPatches pieces = conforming_split(std::move(pieces_in), 1e-10 * size);
  TMeshSurfaceSpace result;
  MultipatchSpace<2>& out = result.space;
  std::vector<int> face_of;
  for (std::size_t i = 0; i < pieces.patches.size(); ++i) {
    face_of.push_back(patches.patches[static_cast<std::size_t>(pieces.owner[i])].face);
    // The space's geometry has the (x, y) of the piece (the plane's map; on a surface only a carrier of the
    // knots and weights), the surface its (x, y, z).
    out.patches.push_back(make_tensor_space(planar ? pieces.patches[i] : keep(pieces.patches[i], 2), 3, subdivisions));
    if (!planar) result.surfaces.push_back(refine_uniform(pieces.patches[i], {subdivisions, subdivisions}));
  }
  // Shared sides: sides whose control points coincide (within 1e-10 of the size) in the same or reversed order;
  // their functions are identified in that order (corners through the chains of sides, so the N corners at a
  // star point become one function). Matching whole sides, not single points, keeps apart the coincident
  // control points of a degenerate side (a Bezier end condition whose nodes sit on the vertex).
  struct Side {
    int patch;
    Face face;
    std::vector<int> ids;
    std::vector<std::array<double, 3>> x;
    std::array<double, 3> mid{};
    int partner = -1;
  };
  std::vector<Side> sides;
  for (int p = 0; p < out.num_patches(); ++p) {
    const TensorSpace<2>& space = out.patches[static_cast<std::size_t>(p)];
    for (const Face& f : all_faces<2>()) {
      Side sd{p, Face{f.dir, f.side, p}, face_basis(space, f), {}, {}, -1};
      for (int i : sd.ids) {
        std::array<double, 3> x{};
        (planar ? space.geometry : result.surfaces[static_cast<std::size_t>(p)]).control_point(i, x.data());
        sd.x.push_back(x);
        for (std::size_t c = 0; c < 3; ++c) sd.mid[c] += x[c] / static_cast<double>(sd.ids.size());
      }
      sides.push_back(std::move(sd));
    }
  }
  std::vector<std::size_t> order(sides.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return sides[a].mid[0] < sides[b].mid[0]; });
  const double tol = 1e-10 * size;
  const auto near = [&](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return std::abs(a[0] - b[0]) <= tol && std::abs(a[1] - b[1]) <= tol && std::abs(a[2] - b[2]) <= tol;
  };
  std::vector<int> parent;
  std::vector<int> base(static_cast<std::size_t>(out.num_patches()) + 1, 0);  // local function -> union-find slot
  for (int p = 0; p < out.num_patches(); ++p)
    base[static_cast<std::size_t>(p) + 1] = base[static_cast<std::size_t>(p)] + out.patches[static_cast<std::size_t>(p)].num_basis();
  parent.resize(static_cast<std::size_t>(base.back()));
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int i) {
    while (parent[static_cast<std::size_t>(i)] != i) i = parent[static_cast<std::size_t>(i)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
    return i;
  };
  for (std::size_t a = 0; a < order.size(); ++a)
    for (std::size_t b = a + 1; b < order.size() && sides[order[b]].mid[0] - sides[order[a]].mid[0] <= tol; ++b) {
      Side& s = sides[order[a]];
      Side& t = sides[order[b]];
      if (s.patch == t.patch || s.ids.size() != t.ids.size() || !near(s.mid, t.mid)) continue;
      const std::size_t n = s.ids.size();
      bool fwd = true, rev = true;
      for (std::size_t k = 0; k < n; ++k) {
        fwd = fwd && near(s.x[k], t.x[k]);
        rev = rev && near(s.x[k], t.x[n - 1 - k]);
      }
      if (!fwd && !rev) continue;
      require(s.partner < 0 && t.partner < 0, [&] {
        return "T-mesh space: a side of face " + std::to_string(face_of[static_cast<std::size_t>(s.patch)]) + " is shared by more than two faces";
      });
      s.partner = t.patch;
      t.partner = s.patch;
      for (std::size_t k = 0; k < n; ++k) {
        const int i = base[static_cast<std::size_t>(s.patch)] + s.ids[k];
        const int j = base[static_cast<std::size_t>(t.patch)] + t.ids[fwd ? k : n - 1 - k];
        parent[static_cast<std::size_t>(find(j))] = find(i);
      }
    }
  // An unshared side must lie on a side of its face along edges of the mesh's boundary only (the piece's domain
  // is its part of the face's (u, v) in [0, 1]^2; sides 0..3 counter-clockwise from the first corner, as Face
  // {dir 1 lo, dir 0 hi, dir 1 hi, dir 0 lo}; a face side's links divide it by their knot intervals); anything
  // else meets its neighbours only in part, which a conforming multipatch space cannot hold.
  const TMesh& mesh = surface.mesh();
  const auto on_boundary = [&](int face, int k, double a, double b) {
    const auto& loop = mesh.faces[static_cast<std::size_t>(face)];
    const auto first = std::find(loop.begin(), loop.end(), mesh.first_corner(face)) - loop.begin();
    std::vector<const TMeshLink*> links;
    int side = -1;
    double total = 0;
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const TMeshLink& l = mesh.links[static_cast<std::size_t>(loop[(static_cast<std::size_t>(first) + i) % loop.size()])];
      if (l.flag == 0) ++side;
      if (side != k) continue;
      links.push_back(&l);
      total += mesh.intervals[static_cast<std::size_t>(l.edge)];
    }
    double at = 0;
    for (const TMeshLink* l : links) {
      const double next = at + mesh.intervals[static_cast<std::size_t>(l->edge)] / total;
      if (std::min(next, b) - std::max(at, a) > 1e-9 && mesh.links[static_cast<std::size_t>(l->opp)].face >= 0) return false;
      at = next;
    }
    return true;
  };
  for (const Side& sd : sides) {
    if (sd.partner >= 0) continue;
    const Box<2> d = out.patches[static_cast<std::size_t>(sd.patch)].geometry.domain();
    const int k = sd.face.dir == 1 ? (sd.face.side == 0 ? 0 : 2) : (sd.face.side == 0 ? 3 : 1);
    const double edge = k == 0 ? d.lo[1] : k == 1 ? 1 - d.hi[0] : k == 2 ? 1 - d.hi[1] : d.lo[0];
    // The piece's extent along the side, as the fraction of the way from the side's first corner.
    const double a = k == 0 ? d.lo[0] : k == 1 ? d.lo[1] : k == 2 ? 1 - d.hi[0] : 1 - d.hi[1];
    const double b = k == 0 ? d.hi[0] : k == 1 ? d.hi[1] : k == 2 ? 1 - d.lo[0] : 1 - d.lo[1];
    const int face = face_of[static_cast<std::size_t>(sd.patch)];
    require(std::abs(edge) <= 1e-12 && on_boundary(face, k, a, b), [&] {
      return "T-mesh space: side " + std::to_string(k) + " of a piece of face " + std::to_string(face) +
             " has no neighbour but is not on the mesh's boundary: faces do not conform";
    });
    out.boundary.push_back(sd.face);
  }
  std::vector<int> number(parent.size(), -1);
  for (int p = 0; p < out.num_patches(); ++p) {
    std::vector<int>& g = out.global.emplace_back();
    for (int i = 0; i < out.patches[static_cast<std::size_t>(p)].num_basis(); ++i) {
      int& n = number[static_cast<std::size_t>(find(base[static_cast<std::size_t>(p)] + i))];
      if (n < 0) n = out.num_basis++;
      g.push_back(n);
    }
  }
  if (report) *report = {static_cast<int>(std::set<int>(face_of.begin(), face_of.end()).size()), out.num_patches(), patches.corner_patches, patches.deviation};
  return result;
}

}  // namespace

MultipatchSpace<2> t_mesh_space(const TMeshSurface& surface, int subdivisions, TMeshSpaceReport* report) {
  return build_t_mesh_space(surface, subdivisions, report, true).space;
}

TMeshSurfaceSpace t_mesh_surface_space(const TMeshSurface& surface, int subdivisions, TMeshSpaceReport* report) {
  return build_t_mesh_space(surface, subdivisions, report, false);
}

}  // namespace trivar
