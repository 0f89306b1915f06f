#pragma once
// HierarchicalSpline<D>: a spline in a hierarchical space (HB or THB basis, hierarchical_space.hpp): one control
// value per active function (stride = dim + rational values, homogeneous (w*x, ..., w) when rational, as
// TensorSpline), so the spline is sum_i c_i T_i (over the weights when rational).
//
// Refinement keeps the spline exactly (up to rounding): the spaces are nested, and the new coefficients are
//   THB: unchanged for functions that stay active; for a new function tau of level l, the coefficient of tau in
//        the level-l local expansion of the spline on a cell of level l in tau's support that the next domain
//        does not cover (a leaf, or a cell a finer domain cuts; every coarser
//        function is truncated there, so that coefficient is tau's; Speleers and Manni 2016, "preservation of
//        coefficients");
//   HB:  a function that leaves the active set passes c_i times its refinement coefficients to its children
//        of the next level, down to active ones (two-scale relation).
// Evaluation goes through HierarchicalEvaluator (leaf Bezier nets), built on first use after a modification.
#include <memory>
#include <mutex>
#include <span>
#include <vector>

#include "trivar/hier/hierarchical_evaluator.hpp"
#include "trivar/hier/hierarchical_space.hpp"
#include "trivar/spline/bezier_extraction.hpp"
#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

template <int D>
class HierarchicalSpline {
public:
  HierarchicalSpline() = default;
  // Exact conversion: the tensor spline's knots are level 0 (dyadic levels follow), its control values the
  // level-0 coefficients in the same order. Throws trivar::Error for unclamped knot vectors.
  explicit HierarchicalSpline(const TensorSpline<D>& s, HierarchicalBasis basis = HierarchicalBasis::thb);
  // From parts (file readers): coefs holds space.num_basis() * (dim + rational) values. Throws trivar::Error on a
  // size mismatch, dim < 1, a value that is not finite, or a THB weight that is not positive (THB functions are
  // a partition of unity, so positive weights keep the denominator positive; HB weights may be zero or negative:
  // a fine function over still-active coarse ones carries the difference of two expansions).
  HierarchicalSpline(HierarchicalSpace<D> space, int dim, bool rational, std::vector<double> coefs);
  HierarchicalSpline(const HierarchicalSpline& o);
  HierarchicalSpline& operator=(const HierarchicalSpline& o);
  HierarchicalSpline(HierarchicalSpline&&) = default;
  HierarchicalSpline& operator=(HierarchicalSpline&&) = default;

  const HierarchicalSpace<D>& space() const { return space_; }
  Box<D> domain() const { return space_.domain(); }
  int dim() const { return dim_; }
  bool is_rational() const { return rational_; }
  int stride() const { return dim_ + (rational_ ? 1 : 0); }
  std::span<const double> coefs() const { return coefs_; }
  const double* coef(int id) const { return coefs_.data() + static_cast<std::size_t>(id) * stride(); }

  // Refinement keeping the spline (see above); same arguments and results as the space's.
  int refine_cells(int level, std::span<const Ints<D>> cells);
  int refine_elements(std::span<const int> elements);
  int refine_elements_admissible(std::span<const int> elements, int m);
  int refine_functions(std::span<const int> ids);
  int extend_domains(const std::vector<std::vector<Ints<D>>>& cells);
  // The same spline in the other basis (HB <-> THB) over the same hierarchy.
  HierarchicalSpline with_basis(HierarchicalBasis basis) const;

  // Value (dim values), value and first partials ((D + 1) * dim), all partials up to `order`
  // (derivative_index.hpp); u clamped to the domain. Const evaluation is thread-safe.
  void eval(const Param<D>& u, double* out) const { evaluator().eval(space_, u, out); }
  void eval_first_derivatives(const Param<D>& u, double* out) const { evaluator().eval_first_derivatives(space_, u, out); }
  void eval_derivs(const Param<D>& u, int order, double* out) const { evaluator().eval_derivs(space_, u, order, out); }
  // eval at every point (out: u.size() * dim values); threads as parallel_for, bit-identical for any count.
  void eval_many(std::span<const Param<D>> u, std::span<double> out, int threads = 0) const;

  // Bezier net of every leaf element, in element order.
  std::vector<BezierElement<D>> bezier_elements() const;
  const HierarchicalEvaluator<D>& evaluator() const;

private:
  HierarchicalSpace<D> space_;
  int dim_ = 0;
  bool rational_ = false;
  std::vector<double> coefs_;
  mutable std::mutex mutex_;
  mutable std::shared_ptr<const HierarchicalEvaluator<D>> evaluator_;

  template <class Refine>
  int refine(Refine&& how);
};

extern template class HierarchicalSpline<2>;
extern template class HierarchicalSpline<3>;

}  // namespace trivar
