#pragma once
// HierarchicalEvaluator<D>: random-point evaluation of a hierarchical spline. Built once per spline state: the
// Bezier net of every leaf element (the element operator applied to the coefficients, prod (p_k+1) x stride
// values); a point then costs the leaf search (one span search on level 0, one binary search per level below
// the leaf), one Bernstein evaluation per direction and one contraction with the net.
#include <span>
#include <vector>

#include "trivar/hier/hierarchical_space.hpp"

namespace trivar {

template <int D>
class HierarchicalEvaluator {
public:
  // coefs: stride values per active function (homogeneous when rational); threads as parallel_for.
  HierarchicalEvaluator(const HierarchicalSpace<D>& space, int dim, bool rational, std::span<const double> coefs,
                        int threads = 0);

  int stride() const { return dim_ + (rational_ ? 1 : 0); }
  // Bezier net of element e (local_size x stride values, u fastest, homogeneous when rational).
  std::span<const double> net(int e) const;

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
};

extern template class HierarchicalEvaluator<2>;
extern template class HierarchicalEvaluator<3>;

}  // namespace trivar
