#pragma once
// HierarchicalEvaluator<D>: random-point evaluation of a hierarchical spline. Built once per spline state: the
// Bezier net of every leaf element (the local expansion of the coefficients on the leaf, ancestors' expansions
// shared, times the Bezier extraction: prod (p_k+1) x stride values) and a search tree of the cells: a dense
// table of the level-0 cells (a binary search over the level-0 breakpoints) whose entries are leaves or dense tables of
// the refined cell's children. A point costs one span search, a few comparisons per level below level 0, one
// Bernstein evaluation per direction and one contraction with the net (unrolled for equal degrees 1..3).
#include <span>
#include <vector>

#include "trivar/hier/hierarchical_space.hpp"

namespace trivar {

template <int D>
class HierarchicalEvaluator {
public:
  // coefs: stride values per active function (homogeneous when rational).
  HierarchicalEvaluator(const HierarchicalSpace<D>& space, int dim, bool rational, std::span<const double> coefs);

  int stride() const { return dim_ + (rational_ ? 1 : 0); }
  // Bezier net of element e (local_size x stride values, u fastest, homogeneous when rational).
  std::span<const double> net(int e) const;

  // The element containing u (u inside the domain), as HierarchicalSpace::find_element.
  int find_element(const HierarchicalSpace<D>& space, const Param<D>& u) const;

  // Value (dim values) / value and first partials ((D + 1) * dim values: value, d/du_0, ...); u clamped to the
  // domain. The space must be the one the evaluator was built from.
  void eval(const HierarchicalSpace<D>& space, const Param<D>& u, double* out) const;
  void eval_first_derivatives(const HierarchicalSpace<D>& space, const Param<D>& u, double* out) const;
  // All partial derivatives up to total order `order` (derivative_index.hpp ordering), quotient rule when
  // rational: derivative_count(D, order) * dim values.
  void eval_derivs(const HierarchicalSpace<D>& space, const Param<D>& u, int order, double* out) const;

private:
  Ints<D> degrees_{};
  int dim_ = 0;
  bool rational_ = false;
  int local_ = 0;
  std::vector<double> nets_;
  std::vector<Box<D>> boxes_;
  // Search tree: code >= 0 a leaf id, code < 0 the refined cell whose children table starts at -code - 1 in
  // codes_. The level-0 table comes first.
  std::vector<int> codes_;
  int same_degree_ = -1;  // the common degree when all directions share it

  int build_table(const HierarchicalSpace<D>& space, int level, const Ints<D>& lo, const Ints<D>& hi);
  template <int N>
  void eval_fixed(const Box<D>& box, const double* net, const Param<D>& x, double* h) const;
};

extern template class HierarchicalEvaluator<2>;
extern template class HierarchicalEvaluator<3>;

}  // namespace trivar
