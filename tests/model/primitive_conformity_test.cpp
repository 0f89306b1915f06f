// Conformity of the primitives' cells: every pair of faces covering the same points (found by geometry,
// independently of how the primitives were assembled) must carry identical knots, degrees, control points
// and weights once the second face's directions are aligned with the first's.
#include <gtest/gtest.h>

#include <Eigen/Core>

#include "trivar/model/ball.hpp"
#include "trivar/model/cone.hpp"
#include "trivar/model/cylinder.hpp"
#include "trivar/model/torus.hpp"
#include "trivar/spline/iso_extraction.hpp"
#include "trivar/spline/reparametrization.hpp"

using namespace trivar;

namespace {

// A 5 x 5 grid of points on the face: corners alone do not tell faces apart when a cell is closed (the
// torus cells' faces along the angle have only two distinct corners).
using Grid = std::array<Eigen::Vector3d, 25>;

Grid samples(const SplineSurface& f) {
  const auto d = f.domain();
  Grid g;
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 5; ++i)
      f.eval({d.lo[0] + d.extent(0) * i / 4, d.lo[1] + d.extent(1) * j / 4}, g[i + 5 * j].data());
  return g;
}

bool same_in_order(const Grid& a, const Grid& b) {
  for (std::size_t k = 0; k < a.size(); ++k)
    if ((a[k] - b[k]).norm() > 1e-9) return false;
  return true;
}

bool same_set(const Grid& a, const Grid& b) {
  for (const auto& p : a) {
    bool found = false;
    for (const auto& q : b) found = found || (p - q).norm() <= 1e-9;
    if (!found) return false;
  }
  return true;
}

// Largest difference of knots, control points and weights; infinity when degrees or counts differ.
double net_difference(const SplineSurface& a, const SplineSurface& b) {
  double d = 0;
  for (int k = 0; k < 2; ++k) {
    if (a.degree(k) != b.degree(k) || a.knots(k).knots().size() != b.knots(k).knots().size())
      return std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < a.knots(k).knots().size(); ++i)
      d = std::max(d, std::abs(a.knots(k)[static_cast<int>(i)] - b.knots(k)[static_cast<int>(i)]));
  }
  for (int i = 0; i < a.num_coefs(); ++i) {
    Eigen::Vector3d p, q;
    a.control_point(i, p.data());
    b.control_point(i, q.data());
    d = std::max({d, (p - q).norm(), std::abs(a.weight(i) - b.weight(i))});
  }
  return d;
}

struct Summary {
  int shared = 0, boundary = 0;
  double worst = 0;  // largest net difference over the shared pairs
};

Summary glue(const CellComplex& cells) {
  std::vector<SplineSurface> faces;
  for (const auto& c : cells)
    for (const auto& f : boundary_faces(c)) faces.push_back(f);
  std::vector<int> partner(faces.size(), -1);
  Summary s;
  for (std::size_t a = 0; a < faces.size(); ++a)
    for (std::size_t b = a + 1; b < faces.size(); ++b) {
      const auto ca = samples(faces[a]);
      if (!same_set(ca, samples(faces[b]))) continue;
      EXPECT_EQ(partner[a], -1) << "face " << a << " matches more than one face";
      partner[a] = static_cast<int>(b);
      partner[b] = static_cast<int>(a);
      ++s.shared;
      double best = std::numeric_limits<double>::infinity();
      for (int o = 0; o < 8; ++o) {
        SplineSurface g = o & 4 ? swap_directions(faces[b], 0, 1) : faces[b];
        if (o & 1) g = reverse(g, 0);
        if (o & 2) g = reverse(g, 1);
        if (same_in_order(ca, samples(g))) best = std::min(best, net_difference(faces[a], g));
      }
      s.worst = std::max(s.worst, best);
    }
  for (const int p : partner) s.boundary += p < 0;
  return s;
}

}  // namespace

TEST(PrimitiveConformity, Cylinder) {
  const auto s = glue(make_cylinder({.radius = 1.1, .height = 0.7}));
  EXPECT_EQ(s.shared, 8);     // core with 4 outer cells, 4 outer neighbours
  EXPECT_EQ(s.boundary, 14);  // 5 bottom, 5 top, 4 lateral
  EXPECT_LE(s.worst, 1e-12);
}

TEST(PrimitiveConformity, Cone) {
  const auto s = glue(make_cone({.bottom_radius = 1.1, .top_radius = 0.2, .height = 0.7}));
  EXPECT_EQ(s.shared, 8);
  EXPECT_EQ(s.boundary, 14);
  EXPECT_LE(s.worst, 1e-12);
}

TEST(PrimitiveConformity, Ball) {
  const auto s = glue(make_ball({.radius = 1.3, .center = Eigen::Vector3d(1, 2, -0.5)}));
  EXPECT_EQ(s.shared, 18);   // 6 cube faces, 12 cube edges
  EXPECT_EQ(s.boundary, 6);  // the sphere patches
  EXPECT_LE(s.worst, 1e-12);
}

TEST(PrimitiveConformity, Torus) {
  const auto s = glue(make_torus({.major_radius = 2, .minor_radius = 0.7}));
  EXPECT_EQ(s.shared, 13);   // 8 in the section, and each cell's faces at angle 0 and 2 pi
  EXPECT_EQ(s.boundary, 4);  // the outer cells' tube faces
  EXPECT_LE(s.worst, 1e-12);
}

TEST(PrimitiveConformity, Box) {
  const auto s = glue(make_box({.size = Eigen::Vector3d(1, 2, 3), .origin = Eigen::Vector3d(-1, 0, 1)}));
  EXPECT_EQ(s.shared, 0);
  EXPECT_EQ(s.boundary, 6);
}
