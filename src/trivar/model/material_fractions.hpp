#pragma once
// Material fractions: the relative amounts of the model's materials at a point. One rule for every consumer
// (slicing, 3MF, AMF, info): each fraction finite and >= 0 and their sum positive; a consumer divides by the
// sum, so only the proportions matter.
#include <cmath>
#include <span>
#include <string>

#include "trivar/model/vmodel.hpp"

namespace trivar {

// Throws Error("<where>: material fractions (f0, f1, ..) <what is wrong>; fractions must be finite and >= 0
// with a positive sum").
[[noreturn]] void reject_material_fractions(std::span<const double> fractions, const std::string& where);

// The sum of the fractions after checking the rule; `where` (a callable returning the location, e.g.
// "cell 2 at parameter (0.5, 0, 1)") is only called on failure, so this is cheap per pixel or vertex.
template <class Where>
double material_fraction_sum(std::span<const double> fractions, Where&& where) {
  double sum = 0;
  bool ok = true;
  for (double f : fractions) {
    ok = ok && std::isfinite(f) && f >= 0;
    sum += f;
  }
  if (!ok || !(sum > 0) || !std::isfinite(sum)) reject_material_fractions(fractions, where());
  return sum;
}

// "cell C at parameter (u, v, w)": the location of a fraction evaluated from a cell attribute.
std::string cell_point(int cell, const Param<3>& u);

// Checks attribute `name` of every cell that has it on a 3 x 3 x 3 grid of its parameter domain (corners, edge
// and face midpoints, centre). Every consumer runs this first, so one bad model gives the same error whatever
// it is sliced or exported to.
void check_material_fractions(const VModel& model, const std::string& name = "material");

}  // namespace trivar
