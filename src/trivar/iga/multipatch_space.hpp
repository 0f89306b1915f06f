#pragma once
// MultipatchSpace<D>: the isogeometric space of a conforming multipatch domain, e.g. the cells of a glued
// V-model. Every patch keeps its own TensorSpace (and so its own Bezier-element loop); basis functions on a
// shared face are identified with their twins on the neighbour face, which makes the space C^0 across the
// interfaces; a cell that meets itself (a closed ring, as in a torus) is identified across its own faces.
// Global scalar unknowns are numbered patch by patch in first-appearance order (a single patch
// keeps its own numbering); an unknown with m components is numbered component-major over the global basis.
//
// A collapsed (degenerate) cell face, as at the axis of a polar parametrisation, carries several basis
// functions at each point of the curve or point it collapses to; those are identified as well, so the
// discrete solution is single-valued there.
#include <vector>

#include <Eigen/Core>

#include "trivar/iga/tensor_space.hpp"

namespace trivar {

class VModel;

template <int D>
struct MultipatchSpace {
  std::vector<TensorSpace<D>> patches;
  std::vector<std::vector<int>> global;  // per patch: local basis function -> global basis function
  int num_basis = 0;
  std::vector<Face> boundary;  // faces on the domain's boundary (not shared, not collapsed), Face::patch set

  int num_patches() const { return static_cast<int>(patches.size()); }
};

// One patch, numbered as itself; its boundary is all its faces.
template <int D>
MultipatchSpace<D> single_patch_space(TensorSpace<D> space);

// The cells of a glued model, each refined like make_tensor_space(cell, degree, subdivisions). Identical
// refinement of conforming neighbours keeps their shared faces identical. Throws trivar::Error when the model
// is not glued, has non-conforming faces, or when the refined control nets of a shared face do not coincide.
MultipatchSpace<3> multipatch_space(const VModel& model, int degree, int subdivisions);

// The coefficients of one patch (component-major over its local basis) from global ones.
template <int D>
Eigen::VectorXd patch_coefs(const MultipatchSpace<D>& space, int patch, const Eigen::VectorXd& coefs,
                            int components);

}  // namespace trivar
