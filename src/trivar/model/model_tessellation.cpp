#include "trivar/model/model_tessellation.hpp"

#include "trivar/core/error.hpp"
#include "trivar/model/brep_from_surfaces.hpp"
#include "trivar/model/model_boundary.hpp"

namespace trivar {

ModelTessellation tessellate_boundary(const VModel& model, const TessellationOptions& opts) {
  const ModelBoundary boundary = model_boundary(model);
  require(boundary.closed(), "tessellate_boundary: the model's boundary is not closed");
  std::vector<TensorSpline<2>> surfaces;
  for (const BoundaryFace& f : boundary.faces) surfaces.push_back(f.geometry);
  const Brep brep = brep_from_surfaces(std::move(surfaces), {.tolerance = model.topology().tolerance});
  BrepTessellation t = tessellate(brep, opts);

  ModelTessellation out;
  out.cell.reserve(t.origins.size());
  out.param.reserve(t.origins.size());
  for (const VertexOrigin& o : t.origins) {
    const BoundaryFace& f = boundary.faces[o.face];
    const TensorSpline<3>& g = model.cell(f.cell).geometry();
    // The face's (s, t) are the cell's two free directions in increasing order; the fixed one is at an end.
    const int fixed = f.face / 2;
    Param<3> u;
    u[fixed] = f.face % 2 ? g.domain().hi[fixed] : g.domain().lo[fixed];
    for (int k = 0, j = 0; k < 3; ++k)
      if (k != fixed) u[k] = o.uv[j++];
    out.cell.push_back(f.cell);
    out.param.push_back(u);
  }
  out.mesh = std::move(t.mesh);
  return out;
}

}  // namespace trivar
