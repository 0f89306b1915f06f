#pragma once
// Gauss quadrature on the elements of a locally refined space: points of an element box or of one of its sides, and the
// sides that lie on the boundary of the domain. Face integrals (Neumann loads, Dirichlet projection, the
// boundary terms of the error indicator) are sums over the element sides on a domain face; the surface
// measure and normal come from side_measure (boundary_integral.hpp), as for tensor patches.
#include <array>
#include <utility>

#include "trivar/core/error.hpp"
#include "trivar/core/gauss_legendre.hpp"
#include "trivar/iga/boundary_integral.hpp"
#include "trivar/iga/refined_space.hpp"

namespace trivar {

// Gauss points (n per direction) of a box, or of one side of it (dir >= 0: u_dir fixed at the side): calls
// body(u, weight) with the parametric weight.
template <int D, class Body>
void for_each_gauss_point(const Box<D>& box, int n, int dir, int side, Body&& body) {
  const QuadratureRule rule = gauss_legendre(n);
  int count = 1;
  for (int k = 0; k < D; ++k)
    if (k != dir) count *= n;
  for (int q = 0; q < count; ++q) {
    Param<D> u;
    double w = 1;
    for (int k = 0, r = q; k < D; ++k) {
      if (k == dir) {
        u[k] = side == 0 ? box.lo[k] : box.hi[k];
        continue;
      }
      const int i = r % n;
      r /= n;
      u[k] = box.lo[k] + box.extent(k) * rule.nodes[static_cast<std::size_t>(i)];
      w *= box.extent(k) * rule.weights[static_cast<std::size_t>(i)];
    }
    body(u, w);
  }
}

// The volume quadrature of an element: n Gauss points per direction, or for an element of a trimmed space the
// rule of its part inside (built with its own point count) or nothing when it lies outside. body(u, weight).
template <int D, class Body>
void for_each_element_point(const RefinedElement<D>& element, int n, Body&& body) {
  if (element.outside) return;
  if (element.rule.empty()) {
    for_each_gauss_point<D>(element.box, n, -1, 0, body);
    return;
  }
  for (const auto& [u, w] : element.rule) body(u, w);
}

// True when the side (face.dir, face.side) of an element box lies on that face of the domain.
template <int D>
bool on_domain_face(const Box<D>& domain, const Box<D>& box, const Face& face) {
  return face.side == 0 ? box.lo[face.dir] == domain.lo[face.dir] : box.hi[face.dir] == domain.hi[face.dir];
}

// Whether side (face.dir, face.side) of an element lies on the boundary face `face` of the space: of the domain,
// or in a multi-block space of the element's block (Face::patch) and on no interface.
template <int D>
bool on_boundary_face(const RefinedSpace<D>& space, const RefinedElement<D>& element, const Face& face) {
  if (space.blocks.empty()) return on_domain_face(space.domain, element.box, face);
  if (element.block != face.patch || ((element.interface_sides >> (2 * face.dir + face.side)) & 1u)) return false;
  return on_domain_face(space.blocks[static_cast<std::size_t>(element.block)].domain, element.box, face);
}

// The functions non-zero on a boundary face of the space; throws trivar::Error for a face it does not have.
template <int D>
const std::vector<int>& boundary_face_basis(const RefinedSpace<D>& space, const Face& face) {
  const bool multi = !space.blocks.empty();
  require(face.dir >= 0 && face.dir < D && (face.side == 0 || face.side == 1) && face.patch >= 0 &&
              face.patch < (multi ? static_cast<int>(space.blocks.size()) : 1),
          multi ? "iga: no such face of the multi-block domain" : "iga: no such face of the locally refined domain");
  const auto k = static_cast<std::size_t>(2 * face.dir + face.side);
  return multi ? space.blocks[static_cast<std::size_t>(face.patch)].face_basis[k] : space.face_basis[k];
}

// Gauss points (n^(D-1)) on the side (dir, side) of one element: calls body(u, p, weight, normal) with the
// element evaluated at u, weight = surface measure times Gauss weight and the unit normal pointing out of the
// element box.
template <int D, class Body>
void for_each_side_point(const RefinedSpace<D>& geometry, const RefinedElement<D>& element, int dir, int side, int n,
                         Body&& body) {
  RefinedPoint<D> p;
  std::array<double, D> normal;
  for_each_gauss_point<D>(element.box, n, dir, side, [&](const Param<D>& u, double w) {
    refined_point(geometry, element, u, p);
    double measure;
    side_measure<D>(p.J, dir, side, measure, normal);
    body(u, std::as_const(p), measure * w, std::as_const(normal));
  });
}

}  // namespace trivar
