#pragma once
// The element loop of the problems on locally refined spaces (LR, HB, THB): dense element matrices and vectors filled in parallel (one element per
// task, so no locking) at the Gauss points of each element, then scattered into the global system in element
// order (deterministic for any thread count). Element dofs are component-major like the global ones: local
// c * m + l is global c * N + ids[l]. With a part of the elements (element_partition.hpp: here a contiguous run
// of element indices), only those are summed; the rows of other functions stay empty.
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "trivar/core/parallel.hpp"
#include "trivar/iga/element_partition.hpp"
#include "trivar/iga/refined_quadrature.hpp"
#include "trivar/iga/sparse_matrix.hpp"

namespace trivar {

struct RefinedSystem {
  SparseMatrix A;
  Eigen::VectorXd b;
};

// point(p, grad, dV, K, b) adds one Gauss point (p + 1 per direction, or the element's rule on a trimmed space, grad from physical_gradients, dV the
// weighted |det J|) into K (components * m square) and b; sides(element, b) then adds the element's boundary
// loads. Both run inside a parallel region and must not throw.
template <int D, class Point, class Sides>
RefinedSystem assemble_refined_system(const RefinedSpace<D>& geometry, int components, int threads, Point&& point, Sides&& sides,
                                      const ElementPartition& part = {}) {
  const int N = geometry.num_basis;
  const auto& elements = geometry.elements;
  const std::pair<int, int> range = part.layers(static_cast<int>(elements.size()));
  const std::size_t first = static_cast<std::size_t>(range.first), E = static_cast<std::size_t>(range.second - range.first);
  std::vector<Eigen::MatrixXd> Ke(E);
  std::vector<Eigen::VectorXd> be(E);
  parallel_for(static_cast<std::ptrdiff_t>(E), threads, [&](std::ptrdiff_t e) {
    const RefinedElement<D>& el = elements[first + static_cast<std::size_t>(e)];
    const Eigen::Index n = static_cast<Eigen::Index>(el.ids.size()) * components;
    Eigen::MatrixXd& K = Ke[static_cast<std::size_t>(e)];
    Eigen::VectorXd& v = be[static_cast<std::size_t>(e)];
    K = Eigen::MatrixXd::Zero(n, n);
    v = Eigen::VectorXd::Zero(n);
    RefinedPoint<D> p;
    std::vector<double> grad;
    for_each_element_point<D>(el, geometry.degrees[0] + 1, [&](const Param<D>& u, double w) {
      refined_point(geometry, el, u, p);
      const double dV = physical_gradients(p, grad) * w;
      point(std::as_const(p), std::as_const(grad), dV, K, v);
    });
    sides(el, v);
  });
  std::vector<Eigen::Triplet<double>> trip;
  const Eigen::Index n = static_cast<Eigen::Index>(N) * components;
  RefinedSystem out{SparseMatrix(n, n), Eigen::VectorXd::Zero(n)};
  std::vector<int> dofs;
  for (std::size_t e = 0; e < E; ++e) {
    dofs.clear();
    for (int c = 0; c < components; ++c)
      for (int id : elements[first + e].ids) dofs.push_back(c * N + id);
    for (std::size_t i = 0; i < dofs.size(); ++i) {
      out.b[dofs[i]] += be[e][static_cast<Eigen::Index>(i)];
      for (std::size_t j = 0; j < dofs.size(); ++j)
        trip.emplace_back(dofs[i], dofs[j], Ke[e](static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)));
    }
  }
  out.A.setFromTriplets(trip.begin(), trip.end());
  return out;
}

}  // namespace trivar
