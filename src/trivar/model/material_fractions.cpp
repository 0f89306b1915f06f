#include "trivar/model/material_fractions.hpp"

#include <cmath>
#include <vector>

#include "trivar/core/error.hpp"
#include "trivar/core/number_format.hpp"

namespace trivar {

void reject_material_fractions(std::span<const double> fractions, const std::string& where) {
  std::string list, problem;
  double sum = 0;
  for (std::size_t k = 0; k < fractions.size(); ++k) {
    const double f = fractions[k];
    list += (k ? ", " : "") + (std::isnan(f) ? std::string("NaN") : format_number(f));  // 0/0 has its sign bit set
    sum += f;
    if (problem.empty() && !std::isfinite(f)) problem = "fraction " + std::to_string(k) + " is not finite";
    if (problem.empty() && f < 0) problem = "fraction " + std::to_string(k) + " is negative";
  }
  if (problem.empty()) problem = sum > 0 ? "sum to a value that is not finite" : "sum to 0";
  throw Error(where + ": material fractions (" + list + "): " + problem +
              "; fractions must be finite and >= 0 with a positive sum");
}

std::string cell_point(int cell, const Param<3>& u) {
  return "cell " + std::to_string(cell) + " at parameter (" + format_number(u[0]) + ", " + format_number(u[1]) + ", " +
         format_number(u[2]) + ")";
}

void check_material_fractions(const VModel& model, const std::string& name) {
  std::vector<double> f;
  for (int c = 0; c < model.num_cells(); ++c) {
    const VCell& cell = model.cell(c);
    if (!cell.has_attribute(name)) continue;
    f.resize(static_cast<std::size_t>(cell.attribute(name).components()));
    const Box<3> dom = cell.geometry().domain();
    for (int k = 0; k < 27; ++k) {
      Param<3> u;
      for (int d = 0, q = k; d < 3; ++d, q /= 3) u[d] = dom.lo[d] + 0.5 * (q % 3) * dom.extent(d);
      cell.eval_attribute(name, u, f.data());
      material_fraction_sum(f, [&] { return cell_point(c, u); });
    }
  }
}

}  // namespace trivar
