#pragma once
// LRSpline<D>: a locally refined (LR) B-spline of parametric dimension D = 2 or 3 (Dokken, Lyche, Pettersen
// 2013), stored as the project's common form: a collection of scaled tensor-product B-splines (each with
// p_k + 2 local knots per direction, a scaling factor gamma in (0, 1] and a control value) over a box mesh of
// mesh rectangles. The scaled B-splines sum to one everywhere (partition of unity), so the spline is
// sum_i gamma_i B_i(u) c_i. Rational splines store homogeneous control values (w*x, ..., w), as TensorSpline.
#include <array>
#include <map>
#include <vector>

#include "trivar/core/box.hpp"
#include "trivar/lr/lr_bspline.hpp"
#include "trivar/lr/mesh_rectangle.hpp"
#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

template <int D>
class LRSpline {
  static_assert(D == 2 || D == 3, "LR B-splines are surfaces or volumes");

public:
  // B-splines keyed by their concatenated local knots (u knots, then v, then w), so that identical B-splines
  // created by different splits are found and merged.
  using BasisMap = std::map<std::vector<double>, LRBSpline<D>>;

  // Exact conversion: every tensor B-spline becomes an LR B-spline with gamma = 1; the mesh holds one
  // full-domain rectangle per distinct knot value with that knot's multiplicity.
  explicit LRSpline(const TensorSpline<D>& s);

  int dim() const { return dim_; }
  bool is_rational() const { return rational_; }
  int stride() const { return dim_ + (rational_ ? 1 : 0); }
  int degree(int k) const { return degrees_[k]; }
  const Box<D>& domain() const { return domain_; }
  const BasisMap& basis() const { return basis_; }
  int num_basis() const { return static_cast<int>(basis_.size()); }
  const std::vector<MeshRectangle<D>>& mesh() const { return mesh_; }
  const std::vector<Box<D>>& elements() const { return elements_; }

  // Refines by the mesh rectangle r: adds it to the mesh (merged with collinear rectangles of the same
  // multiplicity where the union is a box; where rectangles of different multiplicity overlap, the mesh
  // multiplicity is the largest), splits every B-spline whose support r traverses, repeats until every
  // B-spline has minimal support and merges identical B-splines (gammas summed, control values combined
  // gamma-weighted, so sum gamma_i c_i B_i is unchanged). Returns false, changing nothing, when the mesh
  // already contains r with at least its multiplicity. Throws trivar::Error, changing nothing, when r is
  // malformed (direction, multiplicity outside 1..p+1, value not inside the domain, extent outside the
  // domain or empty), when r ends inside an element or an element face, or when r splits no B-spline
  // support (a rectangle that traverses no support is not an LR refinement).
  // Cost: a scan of all B-splines and a rebuild of the element lookup per call.
  bool insert(const MeshRectangle<D>& r);

  // Value (dim values) at u; parameters outside the domain are clamped to it. Half-open supports, with the
  // right end of the domain closed. Control dimension (plus weight) at most kMaxDegree + 1.
  void eval(const Param<D>& u, double* out) const;
  // Value and first partial derivatives: (D + 1) * dim values, the value then d/du_0, ..., d/du_{D-1}.
  void eval_first_derivatives(const Param<D>& u, double* out) const;

private:
  Ints<D> degrees_{};
  int dim_ = 0;
  bool rational_ = false;
  Box<D> domain_{};
  BasisMap basis_;
  std::vector<MeshRectangle<D>> mesh_;
  std::vector<Box<D>> elements_;
  // For lookup: elements_ bucketed on a uniform grid over the domain, and per element the B-splines whose
  // support contains it (pointers into basis_, stable under map insertion / erasure of other entries).
  Ints<D> grid_{};
  std::vector<std::vector<int>> buckets_;
  std::vector<std::vector<const LRBSpline<D>*>> element_basis_;

  void add_to_mesh(const MeshRectangle<D>& r);
  bool split_once(const std::vector<double>& key, std::vector<std::vector<double>>& queue);
  void add_basis(LRBSpline<D>&& b, std::vector<std::vector<double>>& queue);
  void rebuild_lookup();
  int find_element(const Param<D>& u) const;
  template <bool kDerivs>
  void evaluate(const Param<D>& u, double* out) const;
};

extern template class LRSpline<2>;
extern template class LRSpline<3>;

}  // namespace trivar
