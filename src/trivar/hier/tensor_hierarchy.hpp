#pragma once
// TensorHierarchy<D>: the nested tensor-product spline spaces V^0 ⊂ V^1 ⊂ ... of a hierarchical B-spline
// space (Kraft 1997; Giannelli, Juttler, Speleers 2012). Level l has one knot vector per direction, all of the
// same degree and domain, and level l + 1 contains every knot of level l at least as often (nestedness).
// Levels beyond those given are dyadic: one knot in the middle of every non-empty span.
//
// Cells and functions of a level are addressed per direction by small integers: cell e is the e-th non-empty
// knot span (element) of the level's knot vector, function i its i-th B-spline. A dyadic level is never
// stored: its knots are those of the last given level with every span cut into 2^d equal parts, so cells,
// spans, knots, parents and children follow by index arithmetic and deep hierarchies (an adaptive loop
// reaching level 30 at a corner) cost no memory per level. Given levels keep their knot vectors and the
// parent / child tables between them. Local refinement and Bezier matrices are computed on demand from the
// knots (a few p^3 operations).
#include <array>
#include <memory>
#include <vector>

#include "trivar/core/box.hpp"
#include "trivar/spline/knot_vector.hpp"

namespace trivar {

// A given knot vector and its tables.
struct HierarchyBase {
  KnotVector knots;
  std::vector<double> breaks;     // distinct knot values
  std::vector<int> mult;          // multiplicity of each
  std::vector<int> first_knot;    // index of the first copy of each (one more entry: the knot count)
};

// One level in one direction: 2^shift cells of the level per cell of its base.
class HierarchyAxis {
public:
  HierarchyAxis() = default;
  HierarchyAxis(std::shared_ptr<const HierarchyBase> base, int shift) : base_(std::move(base)), shift_(shift) {}

  int degree() const { return base_->knots.degree(); }
  int num_cells() const { return (static_cast<int>(base_->breaks.size()) - 1) << shift_; }
  int num_knots() const { return base_->first_knot.back() + (static_cast<int>(base_->breaks.size()) - 1) * ((1 << shift_) - 1); }
  int num_functions() const { return num_knots() - degree() - 1; }
  // Breakpoint e (0..num_cells): cell e is [brk(e), brk(e + 1)).
  double brk(int e) const;
  // The knot span index s of cell e (t_s = brk(e) < t_{s+1}): B-splines s-p..s live on it.
  int span(int e) const { return first_index(e) + multiplicity(e) - 1; }
  // count knots from index i.
  void knots(int i, int count, double* out) const;
  // Support of B-spline i: cells [first_cell, end_cell).
  int first_cell(int i) const { return break_of_knot(i); }
  int end_cell(int i) const { return break_of_knot(i + degree() + 1); }
  // The cell containing x (half-open cells, the right end closed), clamped to the domain.
  int cell_of(double x) const;
  const HierarchyBase& base() const { return *base_; }
  const std::shared_ptr<const HierarchyBase>& base_ptr() const { return base_; }
  int shift() const { return shift_; }

private:
  std::shared_ptr<const HierarchyBase> base_;
  int shift_ = 0;

  int first_index(int e) const;
  int multiplicity(int e) const { return (e & ((1 << shift_) - 1)) ? 1 : base_->mult[static_cast<std::size_t>(e >> shift_)]; }
  int break_of_knot(int i) const;
};

template <int D>
class TensorHierarchy {
  static_assert(D == 2 || D == 3, "hierarchical splines are surfaces or volumes");

public:
  // Largest number of cells per direction on any level: cell and function indices are packed into 64-bit keys
  // (hier/cell_key.hpp), 32 bits per direction for surfaces, 21 for volumes.
  static constexpr int kMaxIndex = D == 2 ? (1 << 30) : (1 << 20);

  TensorHierarchy() = default;
  // Level 0 only; the others are dyadic.
  explicit TensorHierarchy(const std::array<KnotVector, D>& level0);
  // Explicit levels (at least one). Throws trivar::Error naming level and direction when degrees or domains
  // differ or a level does not contain the knots of the one below.
  explicit TensorHierarchy(const std::vector<std::array<KnotVector, D>>& levels);

  int num_levels() const { return static_cast<int>(levels_.size()); }
  // Adds dyadic levels until there are n. Throws trivar::Error when a level would exceed kMaxIndex cells in a
  // direction.
  void ensure_levels(int n);

  const Ints<D>& degrees() const { return degrees_; }
  int degree(int k) const { return degrees_[k]; }
  const HierarchyAxis& axis(int level, int k) const { return levels_[static_cast<std::size_t>(level)].axes[k]; }
  // The knot vector of a level (built on demand for dyadic levels: O(knots)).
  KnotVector knots(int level, int k) const;
  Box<D> domain() const;
  Box<D> cell_box(int level, const Ints<D>& cell) const;
  // The first level made by dyadic refinement (the number of given levels).
  int dyadic_from() const { return given_; }

  // Parent cell (level - 1) along direction k of cell c of `level` >= 1, and the children (level + 1) of cell c
  // of `level`: cells [first_child, end_child).
  int parent(int level, int k, int c) const;
  int first_child(int level, int k, int c) const;
  int end_child(int level, int k, int c) const { return first_child(level, k, c + 1); }

  // Local refinement along direction k: for a cell c of level l >= 1 with parent cell e of level l - 1, the
  // (p+1) x (p+1) row-major matrix R with B^{l-1}_{s-p+a} = sum_b R[a (p+1) + b] B^l_{s'-p+b} on c (s, s' the
  // spans of e and c).
  void local_refinement(int level, int k, int cell, double* R) const;
  // Bezier extraction along direction k of cell c of level l: (p+1) x (p+1) row-major, row a the B-spline
  // s-p+a in the Bernstein basis of the cell.
  void local_bezier(int level, int k, int cell, double* C) const;
  // The B-spline i of `level` along direction k in the B-splines of level + 1: B_i = sum_j w[j] B_{first + j}.
  void two_scale(int level, int k, int i, int& first, std::vector<double>& w) const;

private:
  struct Level {
    std::array<HierarchyAxis, D> axes;
    // Given levels after the first: parent of each cell in the level below; given levels followed by a given
    // level: first child of each cell (one more entry).
    std::array<std::vector<int>, D> parent, first_child;
  };
  Ints<D> degrees_{};
  std::vector<Level> levels_;
  int given_ = 1;

  void add_given(const std::array<KnotVector, D>& kv);
};

extern template class TensorHierarchy<2>;
extern template class TensorHierarchy<3>;

}  // namespace trivar
