#pragma once
// HierarchicalSpace<D>: a hierarchical B-spline space of parametric dimension D = 2 or 3 over the nested tensor
// spaces of a TensorHierarchy, in either basis:
//   HB  (Kraft 1997): the B-splines of level l whose support lies in Omega^l but not in Omega^{l+1};
//   THB (Giannelli, Juttler, Speleers 2012): the same functions truncated, trunc^{L} ... trunc^{l+1} B, where
//        trunc^{j} drops from a function written in level-j B-splines the terms of those inside Omega^j.
// Both span the same space; THB functions are non-negative and sum to one, HB functions are independent.
//
// Domains. Omega^0 is the whole domain and Omega^l (l >= 1) is any union of cells of level l, the union over
// m >= l of the cell sets given for level m (G+Smo's box semantics: a domain of level l may cut cells of level
// l - 1 and finer domains extend coarser ones). The space depends on Omega^l only through the cells of level l
// inside it (a support of level l is made of such cells), so those are stored: every cell of level l covered
// by Omega^l, closed under coverage by finer cells. Refinement by marked cells, elements or functions keeps
// the hierarchy aligned (Omega^{l+1} a union of cells of level l); arbitrary domains come from
// extend_domains.
//
// Mesh. The elements are the leaves of the tree whose root cells are those of level 0 and whose cell of level
// l is split into its children when a domain cell of a finer level lies inside it: on a leaf of level m every
// active function is one polynomial (functions of levels <= m are polynomials on cells of level m; finer ones
// vanish outside their domains). Leaf ids are ordered by level, then lexicographically (last direction most
// significant). In an aligned hierarchy the split cells are exactly those covered by the next domain.
//
// Ids. Active functions are numbered by level, then lexicographically in their tensor index (u fastest), so the
// level-0 functions of a converted tensor spline keep its control-point order. Ids are valid until the next
// refinement.
//
// Element operators. On a leaf cell Q of level m the active functions are polynomials; every coarser function is
// written in the level-m B-splines on Q by following Q's ancestors level by level (local refinement matrices,
// Kronecker products of 1-D (p+1) x (p+1) blocks), truncating on the way for THB. This one chain serves the
// Bezier extraction, the evaluation of basis functions and the exchange of coefficients under refinement.
#include <span>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include "trivar/core/box.hpp"
#include "trivar/hier/cell_key.hpp"
#include "trivar/hier/tensor_hierarchy.hpp"

namespace trivar {

enum class HierarchicalBasis { hb, thb };

// "hb", "thb".
const char* to_string(HierarchicalBasis b);

template <int D>
struct HierarchicalFunction {
  int level = 0;
  Ints<D> index{};  // tensor index of the B-spline in its level
};

template <int D>
struct HierarchicalCell {
  int level = 0;
  Ints<D> index{};  // cell index in its level
};

// The active functions on one element and their restrictions: row r of C belongs to function ids[r] and holds
// its coefficients in the element's tensor Bernstein basis (prod (p_k + 1) columns, u fastest). ids ascending;
// functions that vanish on the element (THB truncation) are left out.
template <int D>
struct HierarchicalElement {
  std::vector<int> ids;
  Eigen::MatrixXd C;
  Box<D> box;
};

template <int D>
class HierarchicalSpace {
public:
  HierarchicalSpace() = default;
  // Level 0 of the hierarchy only, all of it active.
  HierarchicalSpace(TensorHierarchy<D> hierarchy, HierarchicalBasis basis);

  HierarchicalBasis basis() const { return basis_; }
  // The same hierarchy and active set in the other basis.
  HierarchicalSpace with_basis(HierarchicalBasis basis) const {
    HierarchicalSpace s = *this;
    s.basis_ = basis;
    return s;
  }
  const TensorHierarchy<D>& hierarchy() const { return h_; }
  const Ints<D>& degrees() const { return h_.degrees(); }
  int degree(int k) const { return h_.degree(k); }
  Box<D> domain() const { return h_.domain(); }
  // Makes the hierarchy hold at least n levels (dyadic beyond those given); the space is unchanged.
  void reserve_levels(int n) { h_.ensure_levels(n); }
  // A cell of `level` in the support of the B-spline (level, index) that lies in Omega^level and is not covered
  // by Omega^{level+1}, or false when there is none (then the function is not active). Finer functions vanish on
  // its uncovered part, so there the spline is the polynomial of the levels up to `level`: a leaf, or a cell a
  // finer domain cuts.
  bool uncovered_cell_in_support(int level, const Ints<D>& index, Ints<D>& cell) const;
  // Levels with a non-empty domain Omega^l.
  int num_levels() const { return static_cast<int>(active_.size()); }
  // Local B-splines on a cell: prod (p_k + 1).
  int local_size() const { return local_size_; }

  int num_basis() const { return offset_.back(); }
  int num_basis(int level) const { return offset_[static_cast<std::size_t>(level) + 1] - offset_[static_cast<std::size_t>(level)]; }
  HierarchicalFunction<D> function(int id) const;
  // Id of the function of `level` with tensor index `index`, -1 when it is not active.
  int find_function(int level, const Ints<D>& index) const;
  // Support of a function's B-spline (for THB the truncated function's support is inside it).
  Box<D> function_support(int id) const;

  int num_elements() const { return static_cast<int>(leaves_.size()); }
  HierarchicalCell<D> element(int e) const;
  Box<D> element_box(int e) const;
  std::vector<Box<D>> element_boxes() const;
  // The element containing u (half-open cells, the right end of the domain closed; u clamped to the domain).
  int find_element(const Param<D>& u) const;
  // Id of the leaf (level, cell), -1 when that cell is not a leaf.
  int find_leaf(int level, const Ints<D>& cell) const;

  // Cell (level, index) inside Omega^level / covered by Omega^{level+1} / split into children in the mesh.
  bool in_domain(int level, const Ints<D>& cell) const;
  bool is_refined(int level, const Ints<D>& cell) const;
  bool is_split(int level, const Ints<D>& cell) const;
  // The cells of level l >= 1 inside Omega^l, sorted keys (hier/cell_key.hpp); empty for level 0.
  std::span<const CellKey> domain_cells(int level) const;
  // B-spline (level, index) has its support inside Omega^level.
  bool function_inside(int level, const Ints<D>& index) const;

  // Refinement: the cells (all of one level, each inside Omega^level) join Omega^{level+1}; adds dyadic levels
  // to the hierarchy when needed. Returns the number of cells that were not refined before. Throws
  // trivar::Error, changing nothing, for a cell outside Omega^level or outside the level's index range.
  int refine_cells(int level, std::span<const Ints<D>> cells);
  // Marked elements (leaf ids): each leaf cell is refined (halved), also a leaf outside its level's domain, which
  // a finer domain cutting its parent left. Returns the number of refined elements.
  int refine_elements(std::span<const int> elements);
  // Marked elements refined so that the mesh stays admissible of class m >= 2 (Buffa and Giannelli 2016;
  // Bracco, Buffa, Giannelli, Vazquez 2019; Carraturo et al. 2019): the functions non-zero on any element
  // belong to at most m successive levels, so at most m prod(p_k + 1) act on it. A marked leaf Q of level l
  // first refines, recursively, its neighbourhood: the leaves of level l - m + 1 meeting the support extension
  // of Q at level l - m + 2 (THB) or l - m + 1 (HB), the union of the supports of that level's B-splines
  // non-zero on Q. The mesh must be admissible of class m before (every aligned mesh refined only this way is).
  // Returns the number of refined elements.
  int refine_elements_admissible(std::span<const int> elements, int m);
  // Marked functions (ids): every cell of the support of each is refined (the HB refinement of Vuong,
  // Giannelli, Juttler, Simeon 2011). Returns the number of newly refined cells.
  int refine_functions(std::span<const int> ids);
  // cells[l] (l >= 1) join Omega^l, and so every Omega^j, j < l (cells[0] must be empty): any cells of the
  // level's mesh, also ones cutting coarser cells. Adds dyadic levels when needed. Returns the number of new
  // domain cells. Throws trivar::Error, changing nothing, for a cell outside the level's index range.
  int extend_domains(const std::vector<std::vector<Ints<D>>>& cells);

  // The element's active functions and Bernstein coefficients.
  HierarchicalElement<D> element_operator(int e) const;
  // The active functions non-zero at u and their values and partial derivatives up to total order `order`
  // (derivative_index.hpp ordering): values[r * derivative_count(D, order) + d] for function ids[r].
  void eval_basis(const Param<D>& u, int order, std::vector<int>& ids, std::vector<double>& values) const;

  // sum_beta coefs[beta] beta written in the local B-splines of `level` on `cell` (local_size() x stride values,
  // function-major, local index u fastest), beta over the active functions of levels <= level: on a cell of
  // level m that is not refined, the local coefficients of the spline with those coefficients (stride values
  // each, homogeneous when rational).
  void local_expansion(int level, const Ints<D>& cell, std::span<const double> coefs, int stride, double* out) const;
  // Memo of the expansions on ancestor cells, which many queries share (every leaf below a cell starts from its
  // expansion): per level, cell key -> expansion. Valid for one state of the space and one coefficient vector
  // (or, for a vector filled level by level, for queries of levels whose coarser coefficients are final).
  struct ExpansionCache {
    std::vector<std::unordered_map<CellKey, std::vector<double>>> levels;
  };
  // As above, the ancestors' expansions taken from or stored into `cache` (the cell's own is not stored).
  void local_expansion(int level, const Ints<D>& cell, std::span<const double> coefs, int stride, double* out,
                       ExpansionCache& cache) const;

private:
  TensorHierarchy<D> h_;
  HierarchicalBasis basis_ = HierarchicalBasis::thb;
  int local_size_ = 1;
  std::vector<std::vector<CellKey>> domain_;   // per level >= 1: sorted cells inside Omega^l (level 0 empty)
  std::vector<std::vector<CellKey>> refined_;  // per level: sorted cells covered by Omega^{l+1}
  std::vector<std::vector<CellKey>> split_;    // per level: sorted cells split in the mesh
  bool aligned_ = true;                        // every Omega^l is the children of the covered cells of l - 1
  std::vector<std::vector<CellKey>> inside_;   // per level >= 1: sorted functions with support in Omega^l
  std::vector<std::vector<CellKey>> active_;   // per level: sorted active functions
  std::vector<int> offset_{0};                 // per level + 1: first id
  std::vector<std::vector<CellKey>> leaf_keys_;  // per level: sorted leaf cells
  std::vector<int> leaf_offset_{0};
  std::vector<std::pair<int, CellKey>> leaves_;

  void rebuild();
  // Validates the cells and adds their children to Omega^{level+1} (no rebuild); the number of cells added.
  int mark(int level, std::span<const Ints<D>> cells);
  // Marks the cells of every level, finest first, and rebuilds; the number of cells added.
  int mark_levels(const std::vector<std::vector<Ints<D>>>& per_level);
  // Adds to each domain the cells of its level covered by the finer domains (the closure the space assumes).
  void close_domains();
  bool cell_in_domain(int level, const Ints<D>& cell) const;
  bool support_in(int level, const Ints<D>& f, const std::vector<CellKey>& cells) const;
  bool support_in_domain(int level, const Ints<D>& f) const;
  // One level of the chain behind element_operator and local_expansion: `count` vectors (local_size() x stride
  // each) of level j - 1 on the parent cell are refined to level j on `cell` (j > 0) and truncated (THB); then
  // add(q, id) is called for every active level-j function on the cell (q its local index).
  template <class AddActive>
  void step(int j, const Ints<D>& cell, int stride, double* rows, int count, AddActive&& add) const;
  const std::vector<double>& cached_expansion(int level, const Ints<D>& cell, std::span<const double> coefs, int stride,
                                              ExpansionCache& cache) const;
  Ints<D> parent(int level, const Ints<D>& cell) const;
  // The children (level + 1) of a cell of `level`: the multi-index range [first_children, end_children).
  Ints<D> first_children(int level, const Ints<D>& cell) const;
  Ints<D> end_children(int level, const Ints<D>& cell) const;
};

extern template class HierarchicalSpace<2>;
extern template class HierarchicalSpace<3>;

}  // namespace trivar
