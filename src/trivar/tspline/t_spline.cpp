#include "trivar/tspline/t_spline.hpp"

#include <cmath>

#include "trivar/core/error.hpp"
#include "trivar/spline/basis.hpp"

namespace trivar {

Box<2> anchor_box(const TSpline& ts, const TNode& n) {
  const TImage& im = ts.image;
  switch (n.kind) {
    case TAnchorKind::vertex: {
      const TVertex& v = im.vertices[static_cast<std::size_t>(n.anchor)];
      return Box<2>{{v.s, v.t}, {v.s, v.t}};
    }
    case TAnchorKind::link: return im.edge_box(im.links[static_cast<std::size_t>(n.anchor)].edge);
    case TAnchorKind::face: return im.face_box(n.anchor);
  }
  return {};
}

void validate(const TSpline& ts) {
  validate(ts.image);
  for (int k = 0; k < 2; ++k)
    require(ts.degrees[k] >= 1 && ts.degrees[k] <= kMaxDegree, [&] {
      return "T-spline: degree " + std::to_string(ts.degrees[k]) + " in direction " + (k == 0 ? "s" : "t") +
             " is outside 1.." + std::to_string(kMaxDegree);
    });
  const auto& nodes = ts.connect.nodes;
  const int nn = static_cast<int>(nodes.size());
  for (int i = 0; i < nn; ++i) {
    const TNode& n = nodes[static_cast<std::size_t>(i)];
    const auto where = [&] { return "T-connect: node " + std::to_string(i) + ": "; };
    const std::size_t count = n.kind == TAnchorKind::vertex ? ts.image.vertices.size()
                              : n.kind == TAnchorKind::link ? ts.image.links.size()
                                                             : ts.image.faces.size();
    require(n.anchor >= 0 && static_cast<std::size_t>(n.anchor) < count,
            [&] { return where() + "its anchor " + std::to_string(n.anchor) + " does not exist"; });
    require(n.point >= 0 && static_cast<std::size_t>(n.point) < ts.pointset.points.size(),
            [&] { return where() + "its point " + std::to_string(n.point) + " does not exist"; });
    const Box<2> a = anchor_box(ts, n);
    for (int k = 0; k < 2; ++k)
      require(ts.degrees[k] % 2 == 0 || a.lo[k] == a.hi[k], [&] {
        return where() + "its anchor has a width in direction " + (k == 0 ? "s" : "t") + " of odd degree";
      });
    for (int d = 0; d < 4; ++d) {
      const int m = n.neighbours[static_cast<std::size_t>(d)];
      if (m < 0) continue;
      require(m < nn && m != i, [&] {
        return where() + "its " + kTDirNames[static_cast<std::size_t>(d)] + " neighbour " + std::to_string(m) +
               " does not exist";
      });
    }
    const RationalPoint& p = ts.pointset.points[static_cast<std::size_t>(n.point)];
    require(std::isfinite(p.w) && p.w > 0 && std::isfinite(p.xyz[0]) && std::isfinite(p.xyz[1]) && std::isfinite(p.xyz[2]),
            [&] { return where() + "its point " + std::to_string(n.point) + " is not finite or its weight not positive"; });
  }
}

}  // namespace trivar
