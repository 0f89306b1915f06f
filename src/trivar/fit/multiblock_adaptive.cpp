#include "trivar/fit/multiblock_adaptive.hpp"

#include <algorithm>

#include "trivar/core/error.hpp"
#include "trivar/lr/dorfler.hpp"
#include "trivar/lr/refinement.hpp"

namespace trivar {

namespace {

// Per block the index of its first element in m.space (a block's elements are consecutive, in its LR order).
template <int D>
std::vector<int> block_offsets(const MultiblockSpace<D>& m) {
  std::vector<int> offset(m.blocks.size() + 1, 0);
  for (int b : m.element_block) ++offset[static_cast<std::size_t>(b) + 1];
  for (std::size_t b = 1; b < offset.size(); ++b) offset[b] += offset[b - 1];
  return offset;
}

// The element of block b (index in m.space) holding u, nudged into the block across its side (dir, end): the
// element on that side of the line u lies on.
template <int D>
int element_at(const MultiblockSpace<D>& m, const std::vector<int>& offset, int b, Param<D> u, int dir, int end) {
  const LRSpline<D>& s = m.blocks[static_cast<std::size_t>(b)];
  u[dir] += (end == 0 ? 1.0 : -1.0) * 1e-9 * s.domain().extent(dir);
  for (int k = 0; k < D; ++k) u[k] = std::clamp(u[k], s.domain().lo[k], s.domain().hi[k]);
  return offset[static_cast<std::size_t>(b)] + s.evaluator().find_element(u);
}

}  // namespace

template <int D>
ElementAcross<D> multiblock_across(const MultiblockSpace<D>& m) {
  return [&m, offset = block_offsets(m)](int e, int dir, int side, const Param<D>& u, Param<D>& v) {
    const RefinedElement<D>& el = m.space.elements[static_cast<std::size_t>(e)];
    if (!((el.interface_sides >> (2 * dir + side)) & 1u)) {
      v = u;
      return element_at(m, offset, el.block, u, dir, 1 - side);
    }
    // The common part holding u (the element side lies in one; u is a point inside it).
    for (const BlockInterface<D>& f : m.interfaces)
      for (int k = 0; k < 2; ++k) {
        const auto kk = static_cast<std::size_t>(k);
        if (f.block[kk] != el.block || f.side[kk].dir != dir || f.side[kk].end != side) continue;
        bool inside = true;
        for (int a : along_directions<D>(f.side[kk]))
          inside = inside && u[a] >= std::min(f.lo[kk][a], f.hi[kk][a]) && u[a] <= std::max(f.lo[kk][a], f.hi[kk][a]);
        if (!inside) continue;
        v = interface_param(f, k, u);
        const DomainSide other = f.side[1 - kk];
        return element_at(m, offset, f.block[1 - kk], v, other.dir, other.end);
      }
    throw Error("multiblock: an element side marked as interface lies on no interface of block " + std::to_string(el.block));
  };
}

template <int D>
std::vector<ConvergenceRow> adaptive_poisson(MultiblockSpace<D>& m, const PoissonProblem<D>& problem,
                                             const ExactSolution<D>& exact, const AdaptiveOptions& options,
                                             const std::function<void(const ConvergenceRow&)>& report,
                                             Eigen::VectorXd* coefs, int threads, const RefinedPoissonSolve<D>& solve) {
  AdaptiveModel<D> model;
  model.space = [&m]() -> const RefinedSpace<D>& { return m.space; };
  // The neighbours of the current model (its element offsets), rebuilt with it.
  ElementAcross<D> across = multiblock_across(m);
  model.across = [&across](int e, int dir, int side, const Param<D>& u, Param<D>& v) { return across(e, dir, side, u, v); };
  model.refine = [&](std::span<const double> eta) {
    const std::vector<int> offset = block_offsets(m);
    std::vector<std::vector<int>> marked(m.blocks.size());
    for (int e : dorfler_mark(eta, options.beta)) {
      const int b = m.element_block[static_cast<std::size_t>(e)];
      marked[static_cast<std::size_t>(b)].push_back(e - offset[static_cast<std::size_t>(b)]);
    }
    std::vector<LRSpline<D>> blocks = std::move(m.blocks);
    for (std::size_t b = 0; b < blocks.size(); ++b)
      if (!marked[b].empty()) refine_elements(blocks[b], marked[b], options.refine);
    m = multiblock_space(std::move(blocks));
    across = multiblock_across(m);
  };
  return adaptive_poisson<D>(model, problem, exact, options, report, coefs, threads, solve);
}

#define TRIVAR_INSTANTIATE(D)                                                                                     \
  template ElementAcross<D> multiblock_across(const MultiblockSpace<D>&);                                        \
  template std::vector<ConvergenceRow> adaptive_poisson(MultiblockSpace<D>&, const PoissonProblem<D>&,            \
                                                        const ExactSolution<D>&, const AdaptiveOptions&,          \
                                                        const std::function<void(const ConvergenceRow&)>&,        \
                                                        Eigen::VectorXd*, int, const RefinedPoissonSolve<D>&);
TRIVAR_INSTANTIATE(2)
TRIVAR_INSTANTIATE(3)
#undef TRIVAR_INSTANTIATE

}  // namespace trivar
