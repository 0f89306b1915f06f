#include "trivar/iga/convergence_table.hpp"

#include <cmath>
#include <limits>
#include <ostream>

#include "trivar/core/atomic_file.hpp"
#include "trivar/core/number_format.hpp"
#include "trivar/iga/loglog_plot.hpp"

namespace trivar {

double observed_rate(const std::vector<ConvergenceRow>& rows, std::size_t i, int dim, bool h1) {
  if (i == 0 || i >= rows.size()) return std::numeric_limits<double>::quiet_NaN();
  const double e0 = h1 ? rows[i - 1].h1 : rows[i - 1].l2, e1 = h1 ? rows[i].h1 : rows[i].l2;
  if (!(e0 > 0 && e1 > 0) || rows[i].elements == rows[i - 1].elements) return std::numeric_limits<double>::quiet_NaN();
  return -dim * std::log(e1 / e0) / std::log(static_cast<double>(rows[i].elements) / rows[i - 1].elements);
}

void write_convergence_csv(const std::string& path, const std::vector<ConvergenceRow>& rows, int dim) {
  write_file_atomically(path, [&](std::ostream& os) {
    os << "step,elements,dofs,l2_error,h1_error,l2_rate,h1_rate,estimate,assembly_s,solve_s\n";
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const ConvergenceRow& r = rows[i];
      auto num = [&](double x) {
        if (std::isfinite(x) && x >= 0) write_number(os, x);
        os << ',';
      };
      os << r.step << ',' << r.elements << ',' << r.dofs << ',';
      num(r.l2);
      num(r.h1);
      const double rl2 = observed_rate(rows, i, dim, false), rh1 = observed_rate(rows, i, dim, true);
      if (std::isfinite(rl2)) write_number(os, rl2);
      os << ',';
      if (std::isfinite(rh1)) write_number(os, rh1);
      os << ',';
      num(r.estimate);
      write_number(os, r.assembly_seconds);
      os << ',';
      write_number(os, r.solve_seconds);
      os << '\n';
    }
  });
}

void write_convergence_svg(const std::string& path, const std::vector<ConvergenceRow>& rows) {
  // Unknown errors and missing estimates are negative, so the plot skips them; a study without estimates
  // shows two series and no legend entry for the third.
  std::vector<PlotSeries> series{{{}, {}, {30, 80, 220}, "L2 error"},
                                 {{}, {}, {220, 40, 40}, "H1 error"},
                                 {{}, {}, {40, 150, 60}, "estimate"}};
  for (const auto& r : rows) {
    const double values[] = {r.l2, r.h1, r.estimate};
    for (std::size_t k = 0; k < series.size(); ++k) {
      series[k].x.push_back(r.dofs);
      series[k].y.push_back(values[k]);
    }
  }
  write_loglog_plot(path, series, {.x_label = "degrees of freedom", .y_label = "error"});
}

}  // namespace trivar
