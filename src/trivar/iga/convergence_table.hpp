#pragma once
// Convergence studies: one row per discretisation (uniform refinement level or adaptive step), written as CSV
// and as a log-log SVG plot of the errors against the number of dofs.
#include <string>
#include <vector>

namespace trivar {

struct ConvergenceRow {
  int step = 0;
  int elements = 0;        // elements of the mesh
  int dofs = 0;            // free dofs
  double l2 = 0, h1 = 0;   // errors (negative when unknown)
  double estimate = -1;    // a-posteriori estimate (negative when not computed)
  double assembly_seconds = 0, solve_seconds = 0;
};

// Observed order of convergence between rows i-1 and i with respect to the mesh size h ~ elements^(-1/dim):
// -dim * log(e_i / e_{i-1}) / log(elements_i / elements_{i-1}) (log2 of the error ratio when uniform
// refinement halves h); NaN for row 0, unknown errors or equal element counts.
double observed_rate(const std::vector<ConvergenceRow>& rows, std::size_t i, int dim, bool h1);

// Header step,elements,dofs,l2_error,h1_error,l2_rate,h1_rate,estimate,assembly_s,solve_s; written atomically.
void write_convergence_csv(const std::string& path, const std::vector<ConvergenceRow>& rows, int dim);

// L2 (blue) and H1 (red) error and, where computed, the estimate (green) against dofs on log-log axes with
// decade grid lines, tick values, axis labels and a legend.
void write_convergence_svg(const std::string& path, const std::vector<ConvergenceRow>& rows);

}  // namespace trivar
