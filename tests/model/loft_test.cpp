#include "trivar/model/loft.hpp"

#include <gtest/gtest.h>

#include <string>

#include <Eigen/Core>

#include "support/spline_fixtures.hpp"
#include "trivar/core/error.hpp"
#include "trivar/spline/affine_transform.hpp"

using namespace trivar;

namespace {

template <int D>
void expect_interpolates(const TensorSpline<D>& s, const std::vector<TensorSpline<D - 1>>& sections,
                         const std::vector<double>& params) {
  std::vector<double> x(s.dim()), y(s.dim());
  for (std::size_t j = 0; j < sections.size(); ++j)
    for (const auto& u : test::random_params(sections[j], 100, static_cast<unsigned>(j))) {
      Param<D> t;
      for (int k = 0; k + 1 < D; ++k) t[k] = u[k];
      t[D - 1] = params[j];
      sections[j].eval(u, x.data());
      s.eval(t, y.data());
      for (int d = 0; d < s.dim(); ++d) ASSERT_NEAR(x[d], y[d], 1e-12) << "section " << j;
    }
}

}  // namespace

TEST(Loft, VolumeInterpolatesIncompatibleSurfaces) {
  const std::vector<SplineSurface> sections{test::random_spline<2>({2, 3}, {3, 2}, 3, false, 1),
                                            test::random_spline<2>({1, 2}, {2, 4}, 3, false, 2),
                                            test::random_spline<2>({3, 1}, {1, 3}, 3, false, 3, false),
                                            test::random_spline<2>({2, 2}, {2, 2}, 3, false, 4)};
  const std::vector<double> params{0.0, 0.2, 0.7, 1.0};
  for (int degree : {1, 2, 3}) {
    const auto vol = loft<3>(sections, params, degree);
    EXPECT_EQ(vol.degree(2), degree);
    expect_interpolates(vol, sections, params);
  }
}

TEST(Loft, RationalSectionsAreInterpolatedExactly) {
  // Degree 1 interpolates the homogeneous nets themselves, so the weights stay positive.
  const std::vector<SplineSurface> sections{test::random_spline<2>({2, 3}, {3, 2}, 3, true, 5),
                                            test::random_spline<2>({1, 2}, {2, 4}, 3, false, 6),
                                            test::random_spline<2>({3, 1}, {1, 3}, 3, true, 7)};
  const std::vector<double> params{0.0, 0.6, 1.0};
  const auto vol = loft<3>(sections, params, 1);
  EXPECT_TRUE(vol.is_rational());
  expect_interpolates(vol, sections, params);
  // Higher degrees may overshoot the weights; that is reported as a loft error, not a bad spline.
  const std::vector<SplineSurface> more{sections[0], sections[1], sections[2],
                                        test::random_spline<2>({2, 2}, {2, 2}, 3, true, 8)};
  try {
    loft<3>(more, {0.0, 0.2, 0.7, 1.0}, 3);
    FAIL() << "expected trivar::Error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("loft: interpolated weight", 0), 0u) << e.what();
  }
}

TEST(Loft, SurfaceInterpolatesCurves) {
  std::vector<SplineCurve> sections;
  for (int i = 0; i < 5; ++i)
    sections.push_back(test::random_spline<1>({1 + i % 3}, {2 + i % 2}, 2, false, static_cast<unsigned>(10 + i)));
  const std::vector<double> params{0.0, 0.1, 0.45, 0.5, 1.0};
  expect_interpolates(loft<2>(sections, params, 3), sections, params);
}

TEST(Loft, ChordLengthParametersFollowSectionSpacing) {
  // Translates of one surface by 0, 1, 3, 3.5 along z: chord lengths are exactly those distances.
  const auto base = test::random_spline<2>({2, 2}, {2, 3}, 3, false, 20);
  std::vector<SplineSurface> sections;
  for (double z : {0.0, 1.0, 3.0, 3.5})
    sections.push_back(transform(base, Eigen::MatrixXd::Identity(3, 3), Eigen::Vector3d(0, 0, z)));
  expect_interpolates(loft<3>(sections, 2), sections, {0.0, 1.0 / 3.5, 3.0 / 3.5, 1.0});
}

TEST(Loft, InvalidInputThrows) {
  const std::vector<SplineCurve> two{test::random_spline<1>({2}, {2}, 2, false, 1),
                                     test::random_spline<1>({2}, {2}, 2, false, 2)};
  EXPECT_THROW(loft<2>(two, 2), Error);
  EXPECT_THROW(loft<2>({two[0]}, 1), Error);
  EXPECT_THROW(loft<2>(two, {0.0, 0.0}, 1), Error);
  EXPECT_THROW(loft<2>(two, {0.0, 0.5, 1.0}, 1), Error);
  EXPECT_THROW(loft<2>({two[0], two[0]}, 1), Error);
}
