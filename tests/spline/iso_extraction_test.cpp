#include "trivar/spline/iso_extraction.hpp"

#include <gtest/gtest.h>

#include "support/spline_fixtures.hpp"
#include "trivar/core/error.hpp"

using namespace trivar;

namespace {

// max over random parameters v of the iso entity of |iso(v) - s(v with u inserted at dir)| (reference
// evaluation of s).
template <int D>
double iso_deviation(const TensorSpline<D>& s, const TensorSpline<D - 1>& iso, int dir, double u, unsigned seed) {
  double m = 0;
  std::vector<double> y(iso.dim());
  for (const auto& v : test::random_params(iso, 200, seed)) {
    Param<D> full;
    for (int k = 0, j = 0; k < D; ++k) full[k] = k == dir ? u : v[j++];
    const auto ref = test::reference_eval(s, full);
    iso.eval(v, y.data());
    for (int d = 0; d < s.dim(); ++d) m = std::max(m, std::abs(ref[d] - y[d]));
  }
  return m;
}

}  // namespace

TEST(IsoExtraction, SurfaceIsoCurvesMatchEvaluation) {
  for (bool rational : {false, true}) {
    const auto s = test::random_spline<2>({3, 2}, {4, 3}, 3, rational, 301);
    for (int dir = 0; dir < 2; ++dir)
      for (double f : {0.0, 0.29, 0.5, 1.0}) {
        const double u = s.domain().lo[dir] + f * s.domain().extent(dir);
        const auto c = iso_extract(s, dir, u);
        EXPECT_EQ(c.knots(0), s.knots(1 - dir));
        EXPECT_EQ(c.is_rational(), rational);
        EXPECT_LE(iso_deviation(s, c, dir, u, 302), 1e-12) << "dir " << dir << " u " << u;
      }
  }
}

TEST(IsoExtraction, VolumeIsoSurfacesKeepDirectionOrder) {
  for (bool rational : {false, true})
    for (bool clamped : {true, false}) {
      const auto s = test::random_spline<3>({2, 3, 1}, {3, 2, 4}, 3, rational, 303, clamped);
      for (int dir = 0; dir < 3; ++dir) {
        // At a repeated interior knot as well as at a generic value.
        for (double u : {s.knots(dir).breakpoints()[1], s.domain().lo[dir] + 0.61 * s.domain().extent(dir)}) {
          const auto f = iso_extract(s, dir, u);
          for (int k = 0, j = 0; k < 3; ++k) {
            if (k != dir) {
              EXPECT_EQ(f.knots(j++), s.knots(k));
            }
          }
          EXPECT_LE(iso_deviation(s, f, dir, u, 304), 1e-12);
        }
      }
    }
}

TEST(IsoExtraction, BoundaryFacesOfAVolume) {
  const auto s = test::random_spline<3>({2, 2, 3}, {2, 3, 2}, 3, true, 305);
  const auto faces = boundary_faces(s);
  const auto dom = s.domain();
  for (int k = 0; k < 3; ++k) {
    EXPECT_LE(iso_deviation(s, faces[2 * k], k, dom.lo[k], 306), 1e-12);
    EXPECT_LE(iso_deviation(s, faces[2 * k + 1], k, dom.hi[k], 307), 1e-12);
  }
}

TEST(IsoExtraction, BoundaryCurvesOfASurface) {
  const auto s = test::random_spline<2>({2, 3}, {3, 2}, 2, false, 308);
  const auto edges = boundary_faces(s);
  const auto dom = s.domain();
  for (int k = 0; k < 2; ++k) {
    EXPECT_LE(iso_deviation(s, edges[2 * k], k, dom.lo[k], 309), 1e-12);
    EXPECT_LE(iso_deviation(s, edges[2 * k + 1], k, dom.hi[k], 310), 1e-12);
  }
}

TEST(IsoExtraction, RejectsBadInput) {
  const auto s = test::random_spline<3>({2, 2, 2}, {2, 2, 2}, 3, false, 311);
  EXPECT_THROW(iso_extract(s, 3, 0.5), Error);
  EXPECT_THROW(iso_extract(s, 0, 1.5), Error);
  EXPECT_THROW(iso_extract(s, 2, -0.1), Error);
}
