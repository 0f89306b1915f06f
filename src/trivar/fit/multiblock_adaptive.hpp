#pragma once
// Adaptive refinement of multi-block LR models with T-joints (multiblock_space.hpp): solve on the conforming space,
// estimate per element of every block (the residual indicator, iga/error_indicator.hpp, with the flux jumps across
// the interfaces measured against the neighbour block's elements), mark over all blocks together (Dorfler), refine
// the marked elements of each block inside it by its LR strategy, and match the interfaces again, so the T-joints
// the local refinement makes where it reaches an interface become knot lines of the neighbour's first row and the
// space stays conforming after every step.
#include <functional>
#include <vector>

#include "trivar/fit/multiblock_space.hpp"
#include "trivar/iga/adaptive_loop.hpp"
#include "trivar/iga/error_indicator.hpp"

namespace trivar {

// The element of m.space just across a side of one of its elements: inside the block by the block's own element
// locator, across an interface in the neighbour block at the mapped parameter (interface_param). Refers to m,
// which must outlive it and stay unchanged.
template <int D>
ElementAcross<D> multiblock_across(const MultiblockSpace<D>& m);

// m: the matched initial model, replaced by the model of the last solve (its solution's coefficients to *coefs
// when given). The problem's faces name blocks (Face::patch), e.g. boundary_faces(m): blocks keep their number
// and their sides under refinement. The rest as adaptive_poisson (iga/adaptive_loop.hpp), options.refine the LR
// strategy inside the blocks.
template <int D>
std::vector<ConvergenceRow> adaptive_poisson(MultiblockSpace<D>& m, const PoissonProblem<D>& problem,
                                             const ExactSolution<D>& exact, const AdaptiveOptions& options,
                                             const std::function<void(const ConvergenceRow&)>& report = {},
                                             Eigen::VectorXd* coefs = nullptr, int threads = 0,
                                             const RefinedPoissonSolve<D>& solve = {});

}  // namespace trivar
