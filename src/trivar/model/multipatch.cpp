#include "trivar/model/multipatch.hpp"

#include <algorithm>
#include <cmath>

#include "trivar/core/error.hpp"
#include "trivar/spline/iso_extraction.hpp"

namespace trivar {

MultipatchView multipatch_view(const VModel& model) {
  const VTopology& t = model.topology();
  MultipatchView v;
  for (const auto& c : model.cells()) v.faces.push_back(boundary_faces(c.geometry()));
  v.links.resize(static_cast<std::size_t>(model.num_cells()));
  for (const HalfVSurface& h : t.halves) {
    FaceLink& l = v.links[h.cell][h.face];
    l.degenerate = h.degenerate;
    if (h.twin < 0) continue;
    l.cell = h.twin / 6, l.face = h.twin % 6, l.orientation = h.to_twin;
    l.conforming = t.surfaces[h.surface].conforming;
  }
  for (int c = 0; c < static_cast<int>(t.curves.size()); ++c) {
    const VCurve& cv = t.curves[c];
    const int valence = static_cast<int>(t.cells_around_curve(c).size());
    v.edge_valence.push_back(valence);
    const bool interior = std::none_of(cv.surfaces.begin(), cv.surfaces.end(),
                                       [&](int s) { return t.surfaces[s].boundary(); });
    if (cv.degenerate) v.singular_edges.push_back({c, SingularEdge::Kind::collapsed, valence});
    else if (interior && valence != 4) v.singular_edges.push_back({c, SingularEdge::Kind::interior_valence, valence});
  }
  return v;
}

WatertightReport check_watertight(const VModel& model, double tolerance, int n) {
  require(n >= 2, "watertight check: at least 2 samples per direction needed, got " + std::to_string(n));
  const VTopology& t = model.topology();
  const double tol = tolerance > 0 ? tolerance : t.tolerance;
  WatertightReport r;
  for (int s = 0; s < static_cast<int>(t.surfaces.size()); ++s) {
    const VSurface& vs = t.surfaces[s];
    if (vs.boundary()) continue;
    const HalfVSurface& a = t.halves[vs.halves[0]];
    const HalfVSurface& b = t.halves[vs.halves[1]];
    const TensorSpline<2> fa = boundary_faces(model.cell(a.cell).geometry())[a.face];
    const TensorSpline<2> fb = boundary_faces(model.cell(b.cell).geometry())[b.face];
    const Box<2> da = fa.domain(), db = fb.domain();
    double gap = 0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const Param<2> st{i / (n - 1.0), j / (n - 1.0)};
        const Param<2> m = a.to_twin.map(st);
        double pa[3], pb[3];
        fa.eval({da.lo[0] + st[0] * da.extent(0), da.lo[1] + st[1] * da.extent(1)}, pa);
        fb.eval({db.lo[0] + m[0] * db.extent(0), db.lo[1] + m[1] * db.extent(1)}, pb);
        gap = std::max(gap, std::hypot(pa[0] - pb[0], pa[1] - pb[1], pa[2] - pb[2]));
      }
    r.max_gap = std::max(r.max_gap, gap);
    if (gap > tol) {
      r.watertight = false;
      r.open_surfaces.emplace_back(s, gap);
    }
  }
  return r;
}

}  // namespace trivar
