#include "trivar/model/attribute_blend.hpp"

#include <algorithm>

#include "trivar/core/error.hpp"

namespace trivar {

void blend_union(std::span<const double> a1, std::span<const double> a2, bool in1, bool in2, double d1, double d2,
                 std::span<double> out) {
  require(in1 || in2, "attribute blend: the point lies in neither model");
  require(a1.size() == out.size() && a2.size() == out.size(), "attribute blend: attribute sizes differ");
  double w1 = in1 ? 1.0 : 0.0, w2 = in2 ? 1.0 : 0.0;
  if (in1 && in2) {
    const double sum = d1 + d2;
    w1 = sum > 0 ? d1 / sum : 0.5;
    w2 = 1.0 - w1;
  }
  for (std::size_t k = 0; k < out.size(); ++k) out[k] = (w1 > 0 ? w1 * a1[k] : 0.0) + (w2 > 0 ? w2 * a2[k] : 0.0);
}

UnionBlender::UnionBlender(const VModel& m1, const VModel& m2, std::string attribute)
    : attribute_(std::move(attribute)) {
  const VModel* models[2] = {&m1, &m2};
  for (int s = 0; s < 2; ++s) {
    Side& side = sides_[s];
    side.model = models[s];
    side.boundary = model_boundary(*models[s]);
    for (int c = 0; c < models[s]->num_cells(); ++c) {
      const VCell& cell = models[s]->cell(c);
      const int n = cell.attribute(attribute_).components();
      require(components_ == 0 || n == components_, "attribute blend: attribute '" + attribute_ +
                                                        "' has a different number of components in model " +
                                                        std::to_string(s + 1) + " cell " + std::to_string(c));
      components_ = n;
      side.inverters.emplace_back(cell.geometry());
      Box<3> b;
      cell.geometry().control_bounds(b.lo.data(), b.hi.data());
      side.bounds.push_back(b);
    }
  }
}

bool UnionBlender::sample(const Side& side, const double* x, double* out) const {
  for (std::size_t c = 0; c < side.inverters.size(); ++c) {
    const PointInverter<3>& inv = side.inverters[c];
    if (!side.bounds[c].contains({x[0], x[1], x[2]}, inv.absolute_tolerance())) continue;
    const InversionResult<3> r = inv.invert(x);
    if (!r.found || !r.converged) continue;
    side.model->eval_attribute(static_cast<int>(c), attribute_, r.param, out);
    return true;
  }
  return false;
}

bool UnionBlender::eval(const double* x, double* out) const {
  double* a1 = out;  // the first model's values go straight to out when only it contains x
  std::vector<double> a2(static_cast<std::size_t>(components_));
  const bool in1 = sample(sides_[0], x, a1);
  const bool in2 = sample(sides_[1], x, a2.data());
  if (!in1 && !in2) return false;
  const auto n = static_cast<std::size_t>(components_);
  if (!in1) {
    std::copy(a2.begin(), a2.end(), out);
    return true;
  }
  if (!in2) return true;
  const double d1 = distance_to_boundary(sides_[0].boundary, x);
  const double d2 = distance_to_boundary(sides_[1].boundary, x);
  std::vector<double> first(a1, a1 + n);
  blend_union(first, a2, true, true, d1, d2, {out, n});
  return true;
}

}  // namespace trivar
