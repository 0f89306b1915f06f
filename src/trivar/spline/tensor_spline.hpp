#pragma once
// TensorSpline<D>: a tensor-product B-spline or NURBS of parametric dimension D (1 curve, 2 surface,
// 3 volume), any degree per direction and any control dimension. Control values are stored contiguously,
// u fastest (index i + n0*(j + n1*k)); rational splines are stored homogeneous, (w*x, ..., w), so that every
// linear algorithm (knot insertion, degree elevation, Bezier extraction) works on them unchanged.
#include <array>
#include <span>
#include <vector>

#include "trivar/core/box.hpp"
#include "trivar/spline/knot_vector.hpp"

namespace trivar {

template <int D>
class TensorSpline {
  static_assert(D >= 1 && D <= 3, "TensorSpline supports curves, surfaces and volumes");

public:
  using Index = std::array<int, D>;
  static constexpr int kDim = D;

  TensorSpline() = default;
  // coefs: num_coefs() * stride() values, homogeneous when rational. Throws trivar::Error on a size mismatch, a
  // non-positive control dimension, a value not finite, or weights outside the bounds of tensor_spline.cpp.
  TensorSpline(std::array<KnotVector, D> knots, int dim, bool rational, std::vector<double> coefs);
  // From Cartesian control points (dim values each) and optional weights (empty: polynomial).
  static TensorSpline from_cartesian(std::array<KnotVector, D> knots, int dim, std::span<const double> points,
                                     std::span<const double> weights = {});

  int dim() const { return dim_; }
  bool is_rational() const { return rational_; }
  int stride() const { return dim_ + (rational_ ? 1 : 0); }
  const std::array<KnotVector, D>& knot_vectors() const { return knots_; }
  const KnotVector& knots(int k) const { return knots_[k]; }
  int degree(int k) const { return knots_[k].degree(); }
  int count(int k) const { return knots_[k].size(); }
  Index counts() const;
  int num_coefs() const;
  int linear_index(const Index& i) const;
  Index multi_index(int linear) const;

  std::span<const double> coefs() const { return coefs_; }
  std::span<double> coefs() { return coefs_; }
  const double* coef(int linear) const { return coefs_.data() + static_cast<std::size_t>(linear) * stride(); }
  // Cartesian control point (dim values) and weight (1 for polynomial splines).
  void control_point(int linear, double* x) const;
  double weight(int linear) const { return rational_ ? coef(linear)[dim_] : 1.0; }
  // Bounding box of the Cartesian control points: lo/hi with dim values each. Contains the spline when the
  // weights are positive (convex hull property).
  void control_bounds(double* lo, double* hi) const;

  Box<D> domain() const;

  // Value (dim values) at u. Parameters outside the domain are clamped to it.
  void eval(const Param<D>& u, double* out) const;
  // All partial derivatives up to total order `order` (see derivative_index.hpp for the ordering):
  // derivative_count(D, order) * dim values, rational quotient rule applied.
  void eval_derivs(const Param<D>& u, int order, double* out) const;
  // Batches: out holds u.size() * dim (or * derivative_count * dim) values; threads <= 0 means all.
  void eval_batch(std::span<const Param<D>> u, std::span<double> out, int threads = 0) const;
  void eval_derivs_batch(std::span<const Param<D>> u, int order, std::span<double> out, int threads = 0) const;
  // Tensor grid of parameters (one list per direction); out holds prod(sizes) * dim values, first list
  // fastest. Uses sum factorisation: contracts one direction at a time.
  void eval_grid(const std::array<std::vector<double>, D>& params, std::span<double> out, int threads = 0) const;

private:
  std::array<KnotVector, D> knots_{};
  int dim_ = 0;
  bool rational_ = false;
  std::vector<double> coefs_;
  // Specialised evaluation kernels (eval_kernels.hpp) chosen at construction for common degree / stride pairs
  // and the instruction set of simd_level() (or null).
  void (*fixed_)(const std::array<KnotVector, D>&, const double*, const Param<D>&, double*) = nullptr;
  void (*fixed_d1_)(const std::array<KnotVector, D>&, const double*, const Param<D>&, double*) = nullptr;
  void (*fixed_batch_)(const std::array<KnotVector, D>&, const double*, bool, const Param<D>*, std::size_t,
                       double*) = nullptr;
};

extern template class TensorSpline<1>;
extern template class TensorSpline<2>;
extern template class TensorSpline<3>;

using SplineCurve = TensorSpline<1>;
using SplineSurface = TensorSpline<2>;
using SplineVolume = TensorSpline<3>;

}  // namespace trivar
