#include "trivar/model/model_boundary.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "trivar/spline/closest_point.hpp"
#include "trivar/spline/iso_extraction.hpp"

namespace trivar {

ModelBoundary model_boundary(const VModel& model) {
  const VTopology& t = model.topology();
  ModelBoundary b;
  std::map<int, int> edge_of_curve;
  for (int s = 0; s < static_cast<int>(t.surfaces.size()); ++s) {
    const VSurface& vs = t.surfaces[s];
    if (!vs.boundary()) continue;
    const HalfVSurface& h = t.halves[vs.halves[0]];
    const TensorSpline<3>& g = model.cell(h.cell).geometry();
    BoundaryFace f;
    f.surface = s, f.cell = h.cell, f.face = h.face, f.curves = vs.curves;
    const int d = face_direction(h.face);
    f.geometry = iso_extract(g, d, face_side(h.face) ? g.knots(d).end() : g.knots(d).start());
    // For det J > 0, S_s x S_t is +S_d for d = 0, 2 and -S_d for d = 1 (the order (s, t) skips d), and the
    // outward direction is +S_d on the end side.
    double der[12];
    g.eval_derivs(g.domain().center(), 1, der);
    const double* du = der + 3;
    const double* dv = der + 6;
    const double* dw = der + 9;
    const double det = du[0] * (dv[1] * dw[2] - dv[2] * dw[1]) - du[1] * (dv[0] * dw[2] - dv[2] * dw[0]) +
                       du[2] * (dv[0] * dw[1] - dv[1] * dw[0]);
    const bool outward_if_right_handed = (d != 1) == (face_side(h.face) == 1);
    f.inward = outward_if_right_handed == (det < 0);
    const int fi = static_cast<int>(b.faces.size());
    for (int k = 0; k < 4; ++k) {
      const int c = vs.curves[k];
      if (t.curves[c].degenerate) continue;
      auto [it, added] = edge_of_curve.try_emplace(c, static_cast<int>(b.edges.size()));
      if (added) b.edges.push_back({c, {}});
      b.edges[it->second].uses.emplace_back(fi, k);
    }
    b.faces.push_back(std::move(f));
  }
  return b;
}

double distance_to_boundary(const ModelBoundary& boundary, const double* x) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& f : boundary.faces) {
    double lo[3], hi[3];
    f.geometry.control_bounds(lo, hi);
    double box_dist2 = 0;
    for (int k = 0; k < 3; ++k) {
      const double g = std::max({lo[k] - x[k], x[k] - hi[k], 0.0});
      box_dist2 += g * g;
    }
    if (std::sqrt(box_dist2) >= best) continue;
    best = std::min(best, closest_point(f.geometry, x).distance);
  }
  return best;
}

}  // namespace trivar
