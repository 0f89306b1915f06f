#include "trivar/iga/boundary_integral.hpp"

#include <Eigen/Dense>

#include "trivar/core/gauss_legendre.hpp"
#include "trivar/iga/point_basis.hpp"

namespace trivar {

template <int D>
void side_measure(const std::array<std::array<double, D>, D>& Jarr, int dir, int side, double& weight,
                  std::array<double, D>& normal) {
  Eigen::Matrix<double, D, D> J;
  for (int r = 0; r < D; ++r)
    for (int s = 0; s < D; ++s) J(r, s) = Jarr[r][s];
  const double det = J.determinant();
  // det(J) J^{-T} e_dir is the cofactor column: the area-weighted normal of the face u_dir = const.
  // J^{-T} e_dir is the gradient of u_dir, which points out of the domain at the end side.
  const Eigen::Matrix<double, D, 1> m = det * J.inverse().transpose().col(dir);
  weight = m.norm();
  const double sign = (side == 1 ? 1.0 : -1.0) * (det > 0 ? 1.0 : -1.0);
  for (int k = 0; k < D; ++k) normal[k] = sign * m[k] / weight;
}

template <int D>
void integrate_face(const TensorSpace<D>& space, const Face& face, int points,
                    const std::function<void(const FacePoint<D>&)>& body) {
  const TensorSpline<D>& g = space.geometry;
  const QuadratureRule rule = gauss_legendre(points);
  std::array<std::vector<double>, D> bp;
  int cells = 1;
  for (int k = 0; k < D; ++k)
    if (k != face.dir) {
      bp[k] = g.knots(k).breakpoints();
      cells *= static_cast<int>(bp[k].size()) - 1;
    }
  int per_cell = 1;
  for (int k = 0; k < D - 1; ++k) per_cell *= points;
  const double fixed = face.side == 0 ? g.knots(face.dir).start() : g.knots(face.dir).end();
  PointBasis<D> pb;
  FacePoint<D> fp;
  for (int c = 0; c < cells; ++c)
    for (int q = 0; q < per_cell; ++q) {
      Param<D> u;
      double w = 1;
      for (int k = 0, rc = c, rq = q; k < D; ++k) {
        if (k == face.dir) {
          u[k] = fixed;
          continue;
        }
        const int ne = static_cast<int>(bp[k].size()) - 1;
        const int e = rc % ne, i = rq % points;
        rc /= ne;
        rq /= points;
        const double a = bp[k][static_cast<std::size_t>(e)], b = bp[k][static_cast<std::size_t>(e) + 1];
        u[k] = a + (b - a) * rule.nodes[static_cast<std::size_t>(i)];
        w *= (b - a) * rule.weights[static_cast<std::size_t>(i)];
      }
      point_basis(space, u, pb);
      double len;
      side_measure<D>(pb.J, face.dir, face.side, len, fp.normal);
      fp.x = pb.x;
      fp.weight = len * w;
      fp.ids = pb.ids;
      fp.values = pb.R;
      body(fp);
    }
}

template void side_measure<2>(const std::array<std::array<double, 2>, 2>&, int, int, double&, std::array<double, 2>&);
template void side_measure<3>(const std::array<std::array<double, 3>, 3>&, int, int, double&, std::array<double, 3>&);
template void integrate_face(const TensorSpace<2>&, const Face&, int, const std::function<void(const FacePoint<2>&)>&);
template void integrate_face(const TensorSpace<3>&, const Face&, int, const std::function<void(const FacePoint<3>&)>&);

}  // namespace trivar
