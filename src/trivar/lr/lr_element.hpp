#pragma once
// ElementEvaluator<D>: evaluation data of a collection of scaled tensor-product B-splines over a box partition
// (an LR spline's elements), for fast random-point evaluation without a tensor grid of global knots.
//
// Point location: a k-d tree whose splitting values are element boundaries (elements straddling a split go to
// both sides), built once, O(log E) per point.
// Per element and direction, the distinct univariate B-splines among the element's B-splines (an element of a
// tensor-like region has p + 1 per direction, not (p + 1)^D) are stored as their Bernstein coefficients on the
// element (bernstein_coefficients, precomputed); a point then costs one Bernstein evaluation per direction, a few dot
// products, and one product per B-spline with its gamma * control value.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "trivar/core/box.hpp"
#include "trivar/lr/incidence.hpp"
#include "trivar/lr/lr_bspline.hpp"

namespace trivar {

template <int D>
class ElementEvaluator {
public:
  // element_basis[e]: the ids (into basis) of the B-splines whose support contains elements[e]. Throws
  // trivar::Error when an element has more than 255 distinct univariate B-splines in one direction.
  ElementEvaluator(const Ints<D>& degrees, int dim, bool rational, const Box<D>& domain,
                   std::span<const LRBSpline<D>> basis, std::span<const Box<D>> elements,
                   const Incidence& element_basis);

  // The element containing u (half-open elements, the right end of the domain closed); u inside the domain.
  int find_element(const Param<D>& u) const;
  // Value (dim values) / value and first partials ((D + 1) * dim values); u is clamped to the domain.
  void eval(const Param<D>& u, double* out) const;
  void eval_first_derivatives(const Param<D>& u, double* out) const;

private:
  struct Node {
    int dir = -1;  // -1: leaf
    double value = 0.0;
    int child[2] = {-1, -1};
    int first = 0, count = 0;  // leaf: leaf_elements_[first .. first + count)
  };
  struct Entry {
    int id;
    std::array<std::uint8_t, 4> row;  // per direction, the element's distinct univariate B-spline
  };

  Ints<D> degrees_{};
  int dim_ = 0;
  bool rational_ = false;
  Box<D> domain_{};
  std::vector<Box<D>> elements_;
  std::vector<Node> nodes_;
  // Start nodes of the tree descent: the domain cut into grid_n_[k] equal cells per direction (about one cell
  // per element); each cell keeps the deepest node whose box contains it, so a point skips the levels above it
  // (all of them on a tensor-like mesh) without a data-dependent branch.
  Ints<D> grid_n_{};
  Param<D> grid_scale_{};
  std::array<std::vector<double>, D> grid_bounds_;  // per direction the grid_n_ + 1 cell bounds
  std::vector<int> grid_start_;
  std::vector<int> leaf_elements_;
  std::vector<int> row_start_;      // per (element, direction): offset of its rows in rows_ (doubles)
  std::vector<std::uint8_t> row_count_;
  std::vector<double> rows_;        // Bernstein coefficients, p_k + 1 per row
  std::vector<int> entry_start_;    // per element + 1: its entries in entries_
  std::vector<Entry> entries_;
  std::vector<double> gc_;          // gamma * control value, stride per B-spline
  // Per element, its polynomial as a Bezier block ((p + 1)^D * stride values) when every degree is equal, a
  // kernel exists and the blocks fit kBezierBudget bytes (empty otherwise: evaluation sums the entries).
  static constexpr std::size_t kBezierBudget = std::size_t{64} << 20;
  std::vector<double> blocks_;
  std::size_t block_size_ = 0;
  void (*bezier_value_)(const double*, const Param<D>&, const Param<D>&, double*) = nullptr;
  void (*bezier_first_)(const double*, const Param<D>&, const Param<D>&, double*) = nullptr;

  int build_tree(std::vector<int>& ids, const Box<D>& box, int depth);
  void build_bezier_blocks(int st);
  void build_start_grid();
  template <int kParts>
  void finish(const double* acc, int st, double* out) const;
  template <bool kDerivs, int kStride>
  void evaluate(const Param<D>& u, double* out) const;
  template <bool kDerivs>
  void dispatch(const Param<D>& u, double* out) const;
};

extern template class ElementEvaluator<2>;
extern template class ElementEvaluator<3>;

}  // namespace trivar
