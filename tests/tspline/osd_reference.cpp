#include "osd_reference.hpp"

#include <opensubdiv/bfr/refinerSurfaceFactory.h>
#include <opensubdiv/bfr/surface.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <stdexcept>
#include <string>

namespace trivar::test {

namespace {

namespace osd = OpenSubdiv;
using OsdSurface = osd::Bfr::Surface<double>;

// A point for Far::PrimvarRefiner (the interface its templates expect).
struct OsdPoint {
  std::array<double, 3> x{};
  void Clear() { x = {}; }
  void AddWithWeight(const OsdPoint& p, double w) {
    for (int k = 0; k < 3; ++k) x[k] += w * p.x[k];
  }
};

}  // namespace

struct OsdLimitSurface::Impl {
  std::vector<double> coords;  // the mesh points, three per vertex
  std::unique_ptr<osd::Far::TopologyRefiner> refiner;
  std::unique_ptr<osd::Bfr::RefinerSurfaceFactory<>> factory;

  // The face's surface and its patch points.
  struct Face {
    OsdSurface surface;
    std::vector<double> patch;
  };
  Face face(int f) const {
    Face r;
    if (!factory->InitVertexSurface(f, &r.surface) || !r.surface.IsValid())
      throw std::runtime_error("OpenSubdiv: no limit surface for face " + std::to_string(f));
    r.patch.resize(static_cast<std::size_t>(3 * r.surface.GetNumPatchPoints()));
    r.surface.PreparePatchPoints(coords.data(), OsdSurface::PointDescriptor(3), r.patch.data(), OsdSurface::PointDescriptor(3));
    return r;
  }
  LimitSample eval(const Face& f, double u, double v) const {
    LimitSample s;
    const double uv[2] = {u, v};
    f.surface.Evaluate(uv, f.patch.data(), OsdSurface::PointDescriptor(3), s.p.data(), s.du.data(), s.dv.data());
    return s;
  }
};

OsdLimitSurface::OsdLimitSurface(const PolyMesh& mesh) : impl_(std::make_unique<Impl>()) {
  for (const auto& p : mesh.points) impl_->coords.insert(impl_->coords.end(), p.begin(), p.end());
  std::vector<int> sizes, indices, creases;
  for (const auto& f : mesh.faces) {
    sizes.push_back(static_cast<int>(f.size()));
    indices.insert(indices.end(), f.begin(), f.end());
  }
  for (const auto& e : mesh.sharp_edges) creases.insert(creases.end(), e.begin(), e.end());
  const std::vector<float> weights(mesh.sharp_edges.size(), osd::Sdc::Crease::SHARPNESS_INFINITE);

  osd::Far::TopologyDescriptor desc;
  desc.numVertices = static_cast<int>(mesh.points.size());
  desc.numFaces = static_cast<int>(mesh.faces.size());
  desc.numVertsPerFace = sizes.data();
  desc.vertIndicesPerFace = indices.data();
  desc.numCreases = static_cast<int>(mesh.sharp_edges.size());
  desc.creaseVertexIndexPairs = creases.data();
  desc.creaseWeights = weights.data();
  const std::vector<float> corner_weights(mesh.sharp_vertices.size(), osd::Sdc::Crease::SHARPNESS_INFINITE);
  desc.numCorners = static_cast<int>(mesh.sharp_vertices.size());
  desc.cornerVertexIndices = mesh.sharp_vertices.data();
  desc.cornerWeights = corner_weights.data();

  osd::Sdc::Options options;
  options.SetVtxBoundaryInterpolation(mesh.sharp_corners ? osd::Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER
                                                         : osd::Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
  using Factory = osd::Far::TopologyRefinerFactory<osd::Far::TopologyDescriptor>;
  impl_->refiner.reset(Factory::Create(desc, Factory::Options(osd::Sdc::SCHEME_CATMARK, options)));
  if (!impl_->refiner) throw std::runtime_error("OpenSubdiv: invalid topology");

  osd::Bfr::SurfaceFactory::Options limit;
  limit.SetApproxLevelSmooth(10).SetApproxLevelSharp(10);
  impl_->factory = std::make_unique<osd::Bfr::RefinerSurfaceFactory<>>(*impl_->refiner, limit);
}

OsdLimitSurface::~OsdLimitSurface() = default;

LimitSample OsdLimitSurface::eval(int face, double u, double v) const { return impl_->eval(impl_->face(face), u, v); }

LimitSample OsdLimitSurface::eval_ngon_corner(int face, int corner, double s, double t) const {
  const Impl::Face f = impl_->face(face);
  const osd::Bfr::Parameterization param = f.surface.GetParameterization();
  if (!param.HasSubFaces()) throw std::runtime_error("OpenSubdiv: face " + std::to_string(face) + " has no sub-faces");
  // The sub-face's normalised coordinates map affinely to the face's (u, v): derivatives by the chain rule.
  double o[2], a[2], b[2], uv[2];
  const double st0[2] = {0, 0}, st1[2] = {1, 0}, st2[2] = {0, 1}, st[2] = {s, t};
  param.ConvertNormalizedSubFaceToCoord(corner, st0, o);
  param.ConvertNormalizedSubFaceToCoord(corner, st1, a);
  param.ConvertNormalizedSubFaceToCoord(corner, st2, b);
  param.ConvertNormalizedSubFaceToCoord(corner, st, uv);
  const LimitSample r = impl_->eval(f, uv[0], uv[1]);
  LimitSample out{r.p, {}, {}};
  for (int k = 0; k < 3; ++k) {
    out.du[k] = r.du[k] * (a[0] - o[0]) + r.dv[k] * (a[1] - o[1]);
    out.dv[k] = r.du[k] * (b[0] - o[0]) + r.dv[k] * (b[1] - o[1]);
  }
  return out;
}

std::vector<LimitSample> OsdLimitSurface::vertex_limits(int levels) const {
  // Far's limit masks assume quadrilaterals around the vertex: uniform refinement first (on a copy of the base
  // level, as Bfr's factory needs the refiner unrefined), then the masks at the last level.
  using Factory = osd::Far::TopologyRefinerFactory<osd::Far::TopologyDescriptor>;
  const std::unique_ptr<osd::Far::TopologyRefiner> refiner(Factory::Create(*impl_->refiner));
  osd::Far::TopologyRefiner::UniformOptions uniform(levels);
  uniform.fullTopologyInLastLevel = true;
  refiner->RefineUniform(uniform);
  const std::size_t n = impl_->coords.size() / 3;
  std::vector<OsdPoint> src(n);
  for (std::size_t i = 0; i < n; ++i) src[i].x = {impl_->coords[3 * i], impl_->coords[3 * i + 1], impl_->coords[3 * i + 2]};
  const osd::Far::PrimvarRefinerReal<double> primvar(*refiner);
  std::vector<int> child(n);
  for (std::size_t i = 0; i < n; ++i) child[i] = static_cast<int>(i);
  for (int l = 1; l <= levels; ++l) {
    std::vector<OsdPoint> fine(static_cast<std::size_t>(refiner->GetLevel(l).GetNumVertices()));
    primvar.Interpolate(l, src, fine);
    src = std::move(fine);
    for (int& c : child) c = refiner->GetLevel(l - 1).GetVertexChildVertex(c);
  }
  std::vector<OsdPoint> pos(src.size()), t1(src.size()), t2(src.size());
  primvar.Limit(src, pos, t1, t2);
  std::vector<LimitSample> r(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = static_cast<std::size_t>(child[i]);
    r[i] = {pos[c].x, t1[c].x, t2[c].x};
  }
  return r;
}

}  // namespace trivar::test
