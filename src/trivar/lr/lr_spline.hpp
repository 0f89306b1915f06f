#pragma once
// LRSpline<D>: a locally refined (LR) B-spline of parametric dimension D = 2 or 3 (Dokken, Lyche, Pettersen
// 2013), stored as the project's common form: a collection of scaled tensor-product B-splines (each with
// p_k + 2 local knots per direction, a scaling factor gamma in (0, 1] and a control value) over a box mesh of
// mesh rectangles. The scaled B-splines sum to one everywhere (partition of unity), so the spline is
// sum_i gamma_i B_i(u) c_i. Rational splines store homogeneous control values (w*x, ..., w), as TensorSpline.
//
// Ids. B-splines have dense ids 0..num_basis()-1 in a deterministic order: lexicographic in the local knot
// vectors, the last direction most significant (so a converted tensor spline keeps its multi-index order, u
// fastest). Elements have dense ids 0..num_elements()-1 in the order of their lower corners, lexicographic with
// the last direction most significant (so they depend on the mesh only, not on the refinement history or the
// file format), unless reorder_elements renumbered them (a reader keeping a file's numbering); every
// refinement restores that order. Ids, spans and references are valid until the next modification.
//
// Refinement cost. A batch of rectangles enters the mesh one rectangle at a time (so the mesh, the elements and
// the decision to skip a rectangle are those of one-by-one insertion): a bucket grid finds the elements a
// rectangle touches, which are cut. The B-splines are split afterwards, once for the whole batch: the LR
// B-splines of a mesh do not depend on the order of insertion, so every B-spline on a touched element is tested
// against the final mesh, largest support first, and split by all the lines that cross it in one direction at
// once (a line crosses a support completely when the rectangles of its plane cover the support's cross-section,
// so the test reads the few rectangles of the planes inside the support, not its elements); identical
// B-splines merge through a hash of their knots. Only when the cheap test that a rectangle splits some support
// fails are the pending splits done before it, to test it exactly. So the cost is local to the rectangles.
#include <array>
#include <atomic>
#include <memory>
#include <mutex>
#include <span>
#include <vector>

#include "trivar/core/box.hpp"
#include "trivar/lr/incidence.hpp"
#include "trivar/lr/lr_bspline.hpp"
#include "trivar/lr/lr_element.hpp"
#include "trivar/lr/mesh_rectangle.hpp"
#include "trivar/spline/tensor_spline.hpp"

namespace trivar {

template <int D>
class LRSpline {
  static_assert(D == 2 || D == 3, "LR B-splines are surfaces or volumes");

public:
  // Exact conversion: every tensor B-spline becomes an LR B-spline with gamma = 1; the mesh holds one
  // full-domain rectangle per distinct knot value (domain ends included) with that knot's multiplicity.
  explicit LRSpline(const TensorSpline<D>& s);

  // From parts, for file readers. The domain is the bounding box of the mesh rectangles (which must include
  // the boundary). Validates: degrees 1..kMaxDegree, dim >= 1, p_k + 2 non-decreasing knots per direction
  // spanning a non-empty interval, gamma in (0, 1], stride() coefficients, every support inside the domain,
  // every rectangle well formed (direction, multiplicity 1..p+1, extent non-empty and inside the domain), no
  // rectangle ending inside an element or an element face (a plane given as several rectangles cuts an element
  // where their union crosses it), every support a union of elements, and the scaled B-splines summing to one
  // on every element (exactly, through their Bernstein coefficients; so no B-spline is missing and no element
  // uncovered); throws trivar::Error naming the offending B-spline, rectangle or element. Builds the elements
  // and the support lists; the B-splines are reordered into the id order above.
  LRSpline(const Ints<D>& degrees, int dim, bool rational, std::vector<LRBSpline<D>> basis,
           std::vector<MeshRectangle<D>> mesh);

  int dim() const { return dim_; }
  bool is_rational() const { return rational_; }
  int stride() const { return dim_ + (rational_ ? 1 : 0); }
  int degree(int k) const { return degrees_[k]; }
  const Ints<D>& degrees() const { return degrees_; }
  const Box<D>& domain() const { return domain_; }

  int num_basis() const { return static_cast<int>(basis_.size()); }
  const LRBSpline<D>& basis_function(int id) const { return basis_[static_cast<std::size_t>(id)]; }
  std::span<const LRBSpline<D>> basis_functions() const { return basis_; }
  // Elements in the support of B-spline id, ascending.
  std::span<const int> basis_elements(int id) const { return basis_elements_[id]; }

  int num_elements() const { return static_cast<int>(elements_.size()); }
  const Box<D>& element(int e) const { return elements_[static_cast<std::size_t>(e)]; }
  std::span<const Box<D>> elements() const { return elements_; }
  // B-splines whose support contains element e, ascending.
  std::span<const int> element_support(int e) const { return element_basis_[e]; }

  const std::vector<MeshRectangle<D>>& mesh() const { return mesh_; }

  // Renumbers the elements: element order[i] becomes element i (order is a permutation of the ids), so a reader
  // keeps the numbering of a file that lists its elements. Throws trivar::Error for anything else.
  void reorder_elements(std::span<const int> order);

  // Refines by the mesh rectangle r: adds it to the mesh (merged with collinear rectangles of the same
  // multiplicity where the union is a box; where rectangles of different multiplicity overlap, the mesh
  // multiplicity is the largest), splits every B-spline whose support r traverses, repeats until every
  // B-spline has minimal support and merges identical B-splines (gammas summed, control values combined
  // gamma-weighted, so sum gamma_i c_i B_i is unchanged). Returns false, changing nothing, when the mesh
  // already contains r with at least its multiplicity. Throws trivar::Error, changing nothing, when r is
  // malformed (direction, multiplicity outside 1..p+1, value not inside the domain, extent outside the
  // domain or empty), when r ends inside an element or an element face, or when r splits no B-spline
  // support (a rectangle that traverses no support is not an LR refinement).
  bool insert(const MeshRectangle<D>& r);
  // Inserts the rectangles in order, as insert(r) each, and returns how many changed the spline. Malformed
  // rectangles throw before anything changes. A rectangle that at its turn is already in the mesh or splits
  // no support is skipped (an earlier rectangle of the batch may have covered it). A rectangle that at its turn
  // ends inside an element or face throws; the rectangles before it stay inserted (the spline stays valid).
  int insert(std::span<const MeshRectangle<D>> rects);

  // Value (dim values) at u; parameters outside the domain are clamped to it. Half-open supports, with the
  // right end of the domain closed. Allocation-free after the first call following a modification (which
  // builds the per-element evaluation data, ElementEvaluator); const evaluation is thread-safe.
  void eval(const Param<D>& u, double* out) const;
  // Value and first partial derivatives: (D + 1) * dim values, the value then d/du_0, ..., d/du_{D-1}.
  void eval_first_derivatives(const Param<D>& u, double* out) const;
  // eval at every u (out: u.size() * dim values, point-major); threads as parallel_for (<= 0: all). Every
  // point is evaluated by the same code whatever the thread count, so results are bit-identical.
  void eval_many(std::span<const Param<D>> u, std::span<double> out, int threads = 0) const;
  // eval_first_derivatives at every u (out: u.size() * (D + 1) * dim values).
  void eval_first_derivatives_many(std::span<const Param<D>> u, std::span<double> out, int threads = 0) const;

  // The evaluation data (built on first use after a modification).
  const ElementEvaluator<D>& evaluator() const;

private:
  struct Batch;

  Ints<D> degrees_{};
  int dim_ = 0;
  bool rational_ = false;
  Box<D> domain_{};
  std::vector<LRBSpline<D>> basis_;
  Incidence basis_elements_;  // per B-spline, its elements ascending
  std::vector<Box<D>> elements_;
  Incidence element_basis_;   // per element, its B-splines ascending
  std::vector<MeshRectangle<D>> mesh_;

  // Lazily built evaluation data, shared by copies (it is immutable and holds no references into *this).
  struct LazyEvaluator {
    mutable std::mutex mutex;
    mutable std::atomic<const ElementEvaluator<D>*> ready{nullptr};
    mutable std::shared_ptr<const ElementEvaluator<D>> owner;
    LazyEvaluator() = default;
    LazyEvaluator(const LazyEvaluator& o) { *this = o; }
    LazyEvaluator& operator=(const LazyEvaluator& o) {
      if (this == &o) return *this;
      std::shared_ptr<const ElementEvaluator<D>> p;
      {
        std::lock_guard lock(o.mutex);
        p = o.owner;
      }
      std::lock_guard lock(mutex);
      owner = std::move(p);
      ready.store(owner.get(), std::memory_order_release);
      return *this;
    }
    void reset() {
      std::lock_guard lock(mutex);
      owner.reset();
      ready.store(nullptr, std::memory_order_release);
    }
  };
  LazyEvaluator evaluator_;

  void validate_rectangle(const MeshRectangle<D>& r, const char* who) const;
  void check_partition_of_unity() const;
  void build_support_lists();
  void sort_basis();
};

extern template class LRSpline<2>;
extern template class LRSpline<3>;

}  // namespace trivar
