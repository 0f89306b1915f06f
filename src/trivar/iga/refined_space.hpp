#pragma once
// Analysis on locally refined spaces: LR B-splines and hierarchical (HB, THB) splines, which are all
// collections of (scaled or truncated) tensor B-splines over a box partition. RefinedSpace is what the
// element loop needs from any of them: per element the active functions and their Bezier extraction operator
// (rows in the element's tensor Bernstein basis), the geometry's control points, the functions non-zero on each
// face of the domain and a point locator. One quadrature loop (refined_assembly.hpp), one Dirichlet projection
// and one residual indicator serve every kind; refined_space() builds the space from an LR or a hierarchical
// geometry. The geometry must be polynomial (rational locally refined geometries are not supported by the
// analysis yet).
#include <array>
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "trivar/hier/hierarchical_spline.hpp"
#include "trivar/lr/lr_spline.hpp"
#include "trivar/tspline/t_spline_surface.hpp"

namespace trivar {

// A quadrature point of the trimming boundary of a trimmed space (trimmed_space.hpp) inside an element.
template <int D>
struct TrimmedSidePoint {
  Param<D> u;
  std::array<double, D> normal;  // unit, out of the trimmed domain
  double weight;                 // surface measure times Gauss weight
};

template <int D>
struct RefinedElement {
  std::vector<int> ids;  // active functions on the element, ascending
  Eigen::MatrixXd C;     // extraction operator: ids.size() x prod(p_k + 1), rows include LR scaling factors
  Box<D> box;
  // Trimmed spaces only: the element lies outside the trimmed domain (no quadrature points); the quadrature of
  // its part inside when the trimming boundary cuts it (parametric points and weights, replacing the Gauss
  // rule; empty for an element wholly inside); the points of the trimming boundary inside it.
  bool outside = false;
  std::vector<std::pair<Param<D>, double>> rule;
  std::vector<TrimmedSidePoint<D>> trim_sides;
  // Multi-block spaces only: the block whose parameter domain holds the box, and the sides of the box that lie on
  // an interface between blocks (bit 2 * dir + side), which are not boundary.
  int block = 0;
  unsigned interface_sides = 0;
};

// One block of a multi-block space: its parameter domain and, per face [2 * dir + side], the functions non-zero
// on the part of that face that lies on no interface (the boundary of the union there).
template <int D>
struct RefinedBlock {
  Box<D> domain{};
  std::array<std::vector<int>, 2 * D> face_basis;
};

template <int D>
struct RefinedSpace {
  Ints<D> degrees{};
  Box<D> domain{};
  int num_basis = 0;
  std::vector<double> control;                  // D coordinates per function: the geometry map
  std::vector<RefinedElement<D>> elements;
  std::array<std::vector<int>, 2 * D> face_basis;  // [2 * dir + side]: functions non-zero on that domain face
  std::function<int(const Param<D>&)> locate;   // the element containing a parameter of the domain
  // Multi-block spaces (blocks with their own parameter domains joined along interfaces, possibly with T-joints:
  // fit/multiblock_space): one entry per block, Face::patch names the block, and `domain`, `face_basis` and
  // `locate` are unused. Empty for a space on one domain.
  std::vector<RefinedBlock<D>> blocks;

  int num_elements() const { return static_cast<int>(elements.size()); }
  int degree(int k) const { return degrees[k]; }
};

// The analysis space of an LR geometry (its scaled B-splines, elements and mesh order) or of a hierarchical
// geometry (its HB or THB functions, leaf elements). The locator refers to the geometry, which must outlive the
// space. Throws trivar::Error for a rational or non-D-dimensional geometry.
template <int D>
RefinedSpace<D> refined_space(const LRSpline<D>& geometry, int threads = 0);
template <int D>
RefinedSpace<D> refined_space(const HierarchicalSpline<D>& geometry, int threads = 0);
// The analysis space of a planar T-spline: its blending functions on its Bezier elements (the same extraction
// operators the evaluator uses), geometry (x, y) from the T-pointset. The analysis is the polynomial one, so the
// blending functions must sum to one (standard: every analysis-suitable T-spline is) with all weights 1, the
// points must lie in the plane z = 0 and the T-faces must fill the domain rectangle (sides of the domain are
// the boundary of the analysis). Throws trivar::Error naming the violated condition. The surface must outlive
// the space (its locator).
RefinedSpace<2> refined_space(const TSplineSurface& geometry, int threads = 0);

// The active functions and the geometry at parameter u of an element (u inside its box, boundary included).
template <int D>
struct RefinedPoint {
  std::vector<double> R;    // values
  std::vector<double> dR;   // [l * D + a]: d/du_a
  std::vector<double> d2R;  // [(l * D + a) * D + b]: d2/du_a du_b
  std::array<double, D> x{};
  std::array<std::array<double, D>, D> J{};               // J[c][a] = dx_c/du_a
  std::array<std::array<std::array<double, D>, D>, D> H{};  // H[c][a][b] = d2x_c/du_a du_b
};

template <int D>
void refined_point(const RefinedSpace<D>& space, const RefinedElement<D>& element, const Param<D>& u,
                   RefinedPoint<D>& out);

// Physical gradients grad[l * D + k] = dR_l/dx_k of the active functions at p; returns |det J|.
template <int D>
double physical_gradients(const RefinedPoint<D>& p, std::vector<double>& grad);

}  // namespace trivar
