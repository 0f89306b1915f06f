#pragma once
// Strong Dirichlet conditions: the boundary data is L2-projected onto the trace of the space on the Dirichlet
// faces (one small mass system over the boundary basis functions), which fixes those coefficients; the system
// is then reduced symmetrically (the fixed columns move to the right-hand side, fixed rows become identity
// rows), so the matrix stays symmetric positive definite.
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "trivar/iga/multipatch_space.hpp"
#include "trivar/iga/sparse_matrix.hpp"
#include "trivar/iga/tensor_space.hpp"

namespace trivar {

template <int D>
struct DirichletCondition {
  std::vector<Face> faces;
  std::vector<int> components;  // constrained components (empty: all)
  // Prescribed values of all components at x (null: zero); only the constrained ones are used.
  std::function<void(const double* x, double* u)> value;
};

struct FixedDofs {
  std::vector<char> fixed;  // per dof (component-major)
  Eigen::VectorXd values;   // per dof, zero where free
  int num_free() const;
  // Indices of the free dofs, ascending.
  std::vector<int> free_dofs() const;
};

// Dofs per global basis function (component-major). Throws trivar::Error for a face that is not one of the
// space's (dir, side or patch out of range) or a component out of range.
template <int D>
FixedDofs project_dirichlet(const MultipatchSpace<D>& space, int components,
                            const std::vector<DirichletCondition<D>>& conditions);
template <int D>
FixedDofs project_dirichlet(const TensorSpace<D>& space, int components,
                            const std::vector<DirichletCondition<D>>& conditions);

// A x = b with the fixed dofs eliminated in place (see above).
void apply_dirichlet(SparseMatrix& A, Eigen::VectorXd& b, const FixedDofs& fixed);

// The rows and columns of the free dofs.
SparseMatrix free_block(const SparseMatrix& A, const FixedDofs& fixed);

}  // namespace trivar
