#include "trivar/model/coons.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>

#include "support/spline_fixtures.hpp"
#include "trivar/core/error.hpp"
#include "trivar/model/block.hpp"
#include "trivar/spline/affine_transform.hpp"
#include "trivar/spline/degree_elevation.hpp"
#include "trivar/spline/iso_extraction.hpp"
#include "trivar/spline/knot_insertion.hpp"

using namespace trivar;

TEST(CoonsVolume, ReproducesAffineVolume) {
  const auto block = make_block<3>({2, 3, 2}, {2, 1, 3}, {1.0, 2.0, 1.5});
  Eigen::MatrixXd A(3, 3);
  A << 1.0, 0.3, -0.2, 0.1, 0.9, 0.4, -0.3, 0.2, 1.1;
  const auto vol = transform(block, A, Eigen::Vector3d(0.5, -1.0, 2.0));
  const auto c = coons_volume(boundary_faces(vol));
  EXPECT_LT(test::max_deviation(vol, c, test::random_params(vol, 500, 1)), 1e-12);
}

TEST(CoonsVolume, ReproducesTrilinearVolumeInAnotherBasis) {
  // Random trilinear map (8 random corners), then elevated and refined so the faces carry a richer basis.
  auto vol = test::random_spline<3>({1, 1, 1}, {1, 1, 1}, 3, false, 2);
  vol = elevate_degree(vol, {1, 2, 0});
  const std::vector<double> knots{0.3, 0.7};
  vol = insert_knots(vol, 2, knots);
  const auto c = coons_volume(boundary_faces(vol));
  EXPECT_LT(test::max_deviation(vol, c, test::random_params(vol, 500, 3)), 1e-12);
}

TEST(CoonsVolume, BoundaryFacesMatchInputFaces) {
  for (bool rational : {false, true}) {
    const auto vol = test::random_spline<3>({2, 3, 2}, {3, 2, 2}, 3, rational, 4);
    const auto faces = boundary_faces(vol);
    const auto c = coons_volume(faces);
    const auto out = boundary_faces(c);
    for (int f = 0; f < 6; ++f)
      EXPECT_LT(test::max_deviation(faces[f], out[f], test::random_params(faces[f], 300, 5 + f)), 1e-12)
          << "face " << f << (rational ? " rational" : " polynomial");
  }
}

TEST(CoonsVolume, MismatchedEdgeThrowsNamingFaces) {
  const auto vol = test::random_spline<3>({2, 2, 2}, {2, 2, 2}, 3, false, 6);
  auto faces = boundary_faces(vol);
  // Face u=0 is parametrised by (v, w); its control point (v index 0, interior w index) lies only on the edge
  // shared with face v=0.
  const int j = faces[0].count(1) / 2;
  faces[0].coefs()[3 * faces[0].linear_index({0, j})] += 1e-3;
  try {
    coons_volume(faces);
    FAIL() << "expected trivar::Error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("u=0"), std::string::npos) << what;
    EXPECT_NE(what.find("v=0"), std::string::npos) << what;
    EXPECT_NE(what.find("along w"), std::string::npos) << what;
  }
  // Within a loose tolerance the same faces are accepted.
  EXPECT_NO_THROW(coons_volume(faces, 1e-2));
}
