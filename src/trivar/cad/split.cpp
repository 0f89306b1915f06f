#include "trivar/cad/split.hpp"

#include <cmath>
#include <sstream>

#include "trivar/core/error.hpp"
#include "trivar/core/vec3.hpp"
#include "trivar/model/extrude.hpp"

namespace trivar::cad {

namespace {

using Vec = Vec3;

// The model and the tool swept from `surface` by `sweep`: every piece of the model is kept.
VModel split_by_tool(const VModel& model, const TensorSpline<2>& surface, const Vec& sweep, const BooleanOptions& options,
                     BooleanReport* report) {
  VModel tool;
  tool.add_cell(VCell(extrude<3>(surface, Eigen::Vector3d(sweep[0], sweep[1], sweep[2]))));
  tool.glue();
  BooleanReport rep;
  VModel out = boolean(model, tool, BooleanOp::split, options, &rep);
  require(rep.pieces_both > 0 && rep.pieces_a_only > 0, "split: the surface does not cut the model (every cell lies on one side)");
  if (report) *report = std::move(rep);
  return out;
}

}  // namespace

SplitPlane parse_split_plane(const std::string& text) {
  SplitPlane p;
  std::istringstream in(text);
  char comma = ',';
  for (int k = 0; k < 6 && comma == ','; ++k) {
    double& v = k < 3 ? p.point[static_cast<std::size_t>(k)] : p.normal[static_cast<std::size_t>(k - 3)];
    in >> v;
    if (k < 5) in >> comma;
  }
  require(in && comma == ',' && (in >> std::ws).eof(), "split: plane '" + text + "': expected px,py,pz,nx,ny,nz");
  return p;
}

VModel split(const VModel& model, const SplitPlane& plane, const BooleanOptions& options, BooleanReport* report) {
  const double nn = norm(plane.normal);
  require(nn > 0 && std::isfinite(nn), "split: the plane's normal is zero or not finite");
  const Vec n{plane.normal[0] / nn, plane.normal[1] / nn, plane.normal[2] / nn};
  // A square of the plane around the model's box, twice its diagonal wide, swept along the normal.
  const Box<3> box = model.bounding_box();
  const double r = box.diagonal();
  const Vec c = box.center();
  double off = 0;
  for (int k = 0; k < 3; ++k) off += (c[k] - plane.point[k]) * n[k];
  require(std::abs(off) < 0.5 * r, "split: the plane misses the model's box");
  const Vec o{c[0] - off * n[0], c[1] - off * n[1], c[2] - off * n[2]};
  // An in-plane frame (t1, t2) with t1 x t2 = n.
  const int least = std::abs(n[0]) <= std::abs(n[1]) && std::abs(n[0]) <= std::abs(n[2]) ? 0 : std::abs(n[1]) <= std::abs(n[2]) ? 1 : 2;
  Vec e{};
  e[static_cast<std::size_t>(least)] = 1;
  Vec t1 = cross(e, n);
  const double l1 = norm(t1);
  for (double& x : t1) x /= l1;
  const Vec t2 = cross(n, t1);
  std::vector<double> pts;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i)
      for (int k = 0; k < 3; ++k) pts.push_back(o[k] + r * ((2 * i - 1) * t1[k] + (2 * j - 1) * t2[k]));
  const TensorSpline<2> square = TensorSpline<2>::from_cartesian({KnotVector::open_uniform(1, 1), KnotVector::open_uniform(1, 1)}, 3, pts);
  return split_by_tool(model, square, {2 * r * n[0], 2 * r * n[1], 2 * r * n[2]}, options, report);
}

VModel split(const VModel& model, const TensorSpline<2>& surface, const BooleanOptions& options, BooleanReport* report) {
  require(surface.dim() == 3, "split: the surface is not in 3D (" + std::to_string(surface.dim()) + " coordinates)");
  // The mean normal: S_u x S_v over a grid of the domain.
  const Box<2> dom = surface.domain();
  Vec mean{};
  constexpr int kGrid = 8;
  for (int j = 0; j <= kGrid; ++j)
    for (int i = 0; i <= kGrid; ++i) {
      double d[9];
      surface.eval_derivs({dom.lo[0] + (dom.hi[0] - dom.lo[0]) * i / kGrid, dom.lo[1] + (dom.hi[1] - dom.lo[1]) * j / kGrid}, 1, d);
      const Vec nrm = cross({d[3], d[4], d[5]}, {d[6], d[7], d[8]});
      for (int k = 0; k < 3; ++k) mean[k] += nrm[k];
    }
  const double len = norm(mean);
  require(len > 0 && std::isfinite(len), "split: the surface has no mean normal (closed or degenerate)");
  const double r = model.bounding_box().diagonal();
  return split_by_tool(model, surface, {2 * r * mean[0] / len, 2 * r * mean[1] / len, 2 * r * mean[2] / len}, options, report);
}

}  // namespace trivar::cad
