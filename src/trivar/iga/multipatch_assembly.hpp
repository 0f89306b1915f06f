#pragma once
// Assembly on a multipatch space: every patch is assembled by the tensor-patch assembler (assembler.hpp) with
// its own form, then its rows and columns are renumbered to the global basis and summed. A single patch is
// returned as assembled (its numbering is the global one).
#include <functional>

#include <Eigen/Core>

#include "trivar/iga/assembler.hpp"
#include "trivar/iga/multipatch_space.hpp"

namespace trivar {

// form(patch): the bilinear form on that patch (materials may differ per patch); all with the same components.
// part: the same share of every patch's elements (see the tensor assembler).
template <int D>
SparseMatrix assemble_matrix(const MultipatchSpace<D>& space, const std::function<BilinearForm<D>(int patch)>& form,
                             int threads = 0, const ElementPartition& part = {});

template <int D>
Eigen::VectorXd assemble_load(const MultipatchSpace<D>& space, int components,
                              const std::function<void(const double* x, double* f)>& f, int threads = 0,
                              const ElementPartition& part = {});

// Adds the patch vector b_patch (component-major over the patch's basis) to the global vector b.
template <int D>
void add_patch_vector(const MultipatchSpace<D>& space, int patch, const Eigen::VectorXd& b_patch, int components,
                      Eigen::VectorXd& b);

}  // namespace trivar
