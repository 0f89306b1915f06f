#pragma once
// Multi-block LR models with T-joints (seed 004, "multi-block T-joints"): planar LR (or B-spline) blocks, or volume
// blocks, one template, whose sides (faces) meet over common parts that need not be whole sides (a side of one
// block may border several blocks, so a block corner or edge can lie inside a neighbour's side: a T-joint). The
// blocks are made conforming by
//   1. matching the parametrisation: every common part is found geometrically (the corners of each side that lie
//      on the other bound it) and must correspond linearly, direction by direction, on both sides;
//   2. adjusting the side knot lines (planes): each block receives its neighbours' knots over the common part, and
//      at the part's edges inside the side (T-joints) their parameters with multiplicity p, as LR segments over the
//      first row only (on volumes the neighbour's planes and the T-joint planes span the part, widened to the
//      first-row supports meeting it, not the whole face);
//   3. identifying the transition B-splines: the first-row B-splines that a T-joint's line crosses split there;
//      after the splits each one's trace on a common part equals one neighbour B-spline's trace there, and those
//      are identified as one global function (a B-spline at a T-joint with one function of each block there).
// The result is an analysis space for iga's refined solvers (RefinedSpace with blocks): every block's Bezier
// elements with global function ids. Global functions are the unscaled B-splines (LR scaling factors moved into
// their control points), which makes the traces of identified functions equal, so the space is C0 and conforming
// across every interface.
#include <array>
#include <utility>
#include <vector>

#include "trivar/fit/domain_side.hpp"
#include "trivar/iga/multipatch_space.hpp"
#include "trivar/iga/refined_space.hpp"
#include "trivar/lr/lr_spline.hpp"

namespace trivar {

// A common part of two block sides (faces): a box of each side (its `dir` entry the side's value); corner lo[0]
// of side 0 meets corner lo[1] of side 1, hi likewise, and direction a of side 0 runs along direction
// along[a] of side 1 (so lo[1][along[a]] exceeds hi[1][along[a]] where that direction runs backwards);
// along[side[0].dir] = side[1].dir.
template <int D>
struct BlockInterface {
  std::array<int, 2> block{};
  std::array<DomainSide, 2> side{};
  std::array<Param<D>, 2> lo{}, hi{};
  Ints<D> along{};
};

template <int D>
struct MultiblockSpace {
  std::vector<LRSpline<D>> blocks;            // the blocks after matching (refined near their interfaces)
  std::vector<BlockInterface<D>> interfaces;
  std::vector<std::vector<int>> global;       // per block: B-spline id -> global function
  // All blocks' elements with global ids, one RefinedBlock per block (its domain, its boundary functions per side)
  // and the elements' sides on interfaces marked, so iga's solvers on RefinedSpace take Face{dir, side, block}.
  RefinedSpace<D> space;
  std::vector<int> element_block;             // per element of `space`: its block
  std::vector<int> boundary;                  // global functions non-zero on the boundary of the union, ascending
  std::vector<std::pair<int, DomainSide>> boundary_sides;  // (block, side) not on any interface
  std::vector<std::pair<int, DomainSide>> partial_sides;   // (block, side) partly on interfaces, partly not
};

struct MultiblockOptions {
  // Distance at which points coincide; 0: 1e-8 times the largest control-net diagonal.
  double tolerance = 0.0;
  // Knot lines (planes) across whole blocks instead of the first row only: tensor blocks stay tensor splines
  // (every B-spline crossing a T-joint's line splits, not only the transition ones), as tensor_multipatch needs.
  bool whole_lines = false;
  // Volumes: the edges of a common part inside a face (T-joints) as planes across the whole face instead of over
  // the common part widened to the first-row supports meeting it (splits more B-splines; kept to measure what
  // the local planes save).
  bool whole_face_edges = false;
};

// Steps 1 and 2 alone, on blocks of any number of coordinates (surfaces in space, rational ones too): finds the
// common parts and exchanges the side knot lines (planes) over the first `rows` rows (1 for C0 conformity, 2 for
// C1 stitching; 0 or options.whole_lines: across whole blocks) until every interface's traces agree; the blocks
// are refined in place (geometry unchanged). Throws trivar::Error as multiblock_space for blocks of different
// degrees, coordinates or rationality, and for faces that overlap with no corner of either on the other
// (a plus-shaped overlap, naming both blocks).
template <int D>
std::vector<BlockInterface<D>> match_blocks(std::vector<LRSpline<D>>& blocks, const MultiblockOptions& options, int rows);

// The parameters of side 1 - from of interface f at the point with parameters u on side `from` (u's entry across
// the side is ignored; the result's is the other side's value).
template <int D>
Param<D> interface_param(const BlockInterface<D>& f, int from, const Param<D>& u);

// Planar surfaces (D = 2, two coordinates) or volumes (D = 3, three coordinates). Throws trivar::Error with one
// line for blocks that are not polynomial with D coordinates and equal degrees, faces that overlap with no corner
// of either on the other (plus-shaped, naming both), sides that meet over a common part
// with parametrisations that do not correspond linearly (direction by direction) or with different degrees along
// it, geometry that differs across an interface, or traces that still differ after matching.
template <int D>
MultiblockSpace<D> multiblock_space(std::vector<LRSpline<D>> blocks, const MultiblockOptions& options = {});

// The faces Face{dir, side, block} of the blocks that reach the boundary of the union (wholly or in part): the
// Dirichlet faces of a problem held on the whole boundary.
template <int D>
std::vector<Face> boundary_faces(const MultiblockSpace<D>& m);

// A discrete field on the multi-block space (coefs component-major over the global functions, as iga's solvers
// give them) as one LR spline per block with `components` values, on the block's own B-splines and mesh (each
// B-spline's coefficient is the global function's divided by its scaling factor), for evaluation and output.
template <int D>
std::vector<LRSpline<D>> multiblock_fields(const MultiblockSpace<D>& m, const Eigen::VectorXd& coefs, int components);

// The same model as the tensor multipatch space of iga (MultipatchSpace: one TensorSpace per block and the
// local-to-global map), for its assembler, Dirichlet projection, Poisson and elasticity solvers and error norms.
// Needs blocks that are tensor splines (multiblock_space with whole_lines and tensor inputs) and block sides that
// are either wholly on interfaces or wholly on the boundary; throws trivar::Error naming the block otherwise.
template <int D>
MultipatchSpace<D> tensor_multipatch(const MultiblockSpace<D>& m);

}  // namespace trivar
