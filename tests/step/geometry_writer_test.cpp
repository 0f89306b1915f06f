// The STEP text trivar writes for its objects: entities, the AP242 context, 1-based shared LOCAL_B_SPLINEs.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "hier/hier_test_support.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/step/geometry_reader.hpp"
#include "trivar/io/step/parser.hpp"
#include "trivar/io/step/geometry_writer.hpp"
#include "trivar/io/step/writer.hpp"

using namespace trivar;
using namespace trivar::io::step;

namespace {

std::string text(const ExchangeFile& f) {
  std::ostringstream os;
  write_exchange_file(os, f, {.time_stamp = "2026-01-01T00:00:00", .version = "test", .line_width = 100000});
  return os.str();
}

TensorSpline<2> bilinear() {
  std::array<KnotVector, 2> kv{KnotVector(1, {0, 0, 2, 2}), KnotVector(1, {0, 0, 1, 1})};
  // u fastest: P00, P10, P01, P11.
  return TensorSpline<2>(kv, 3, false, {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 1});
}

}  // namespace

TEST(StepGeometryWriter, PolynomialSurfaceUOutermost) {
  const std::string t = text(geometry_exchange_file({bilinear()}, {}, {.names = {"patch"}}));
  // Points in trivar order, then the grid listed u outermost: ((P00, P01), (P10, P11)).
  EXPECT_NE(t.find("#5=CARTESIAN_POINT('',(0.,0.,0.));\n#6=CARTESIAN_POINT('',(1.,0.,0.));\n"
                   "#7=CARTESIAN_POINT('',(0.,1.,0.));\n#8=CARTESIAN_POINT('',(1.,1.,1.));"),
            std::string::npos)
      << t;
  EXPECT_NE(t.find("#9=B_SPLINE_SURFACE_WITH_KNOTS('patch',1,1,((#5,#7),(#6,#8)),.UNSPECIFIED.,.U.,.U.,.U.,"
                   "(2,2),(2,2),(0.,2.),(0.,1.),.UNSPECIFIED.);"),
            std::string::npos)
      << t;
  EXPECT_NE(t.find("#10=SHAPE_REPRESENTATION('trivar',(#9),#4);"), std::string::npos) << t;
  EXPECT_NE(t.find("FILE_SCHEMA(('AP242_MANAGED_MODEL_BASED_3D_ENGINEERING_MIM_LF { 1 0 10303 442 1 1 4 }'));"),
            std::string::npos);
  EXPECT_NE(t.find("#1=(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.));"), std::string::npos) << t;
  EXPECT_NE(t.find("#2=(NAMED_UNIT(*)PLANE_ANGLE_UNIT()SI_UNIT($,.RADIAN.));"), std::string::npos) << t;
  EXPECT_NE(t.find("#3=(NAMED_UNIT(*)SI_UNIT($,.STERADIAN.)SOLID_ANGLE_UNIT());"), std::string::npos) << t;
  EXPECT_NE(t.find("#4=(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNIT_ASSIGNED_CONTEXT((#1,#2,#3))"
                   "REPRESENTATION_CONTEXT('trivar','3D'));"),
            std::string::npos)
      << t;
}

TEST(StepGeometryWriter, RationalCurveComplexInstance) {
  std::array<KnotVector, 1> kv{KnotVector(2, {0, 0, 0, 1, 1, 1})};
  const double pts[] = {1, 0, 0, 1, 1, 0, 0, 1, 0}, w[] = {1, 0.5, 1};
  ExchangeFile f;
  f.header.schemas = {"TEST"};
  add_spline(f, TensorSpline<1>::from_cartesian(kv, 3, pts, w), "arc");
  const std::string t = text(f);
  EXPECT_NE(t.find("#4=(BOUNDED_CURVE()B_SPLINE_CURVE(2,(#1,#2,#3),.UNSPECIFIED.,.U.,.U.)"
                   "B_SPLINE_CURVE_WITH_KNOTS((3,3),(0.,1.),.UNSPECIFIED.)CURVE()GEOMETRIC_REPRESENTATION_ITEM()"
                   "RATIONAL_B_SPLINE_CURVE((1.,0.5,1.))REPRESENTATION_ITEM('arc'));"),
            std::string::npos)
      << t;
  // Cartesian points: (w x) / w.
  EXPECT_NE(t.find("#2=CARTESIAN_POINT('',(1.,1.,0.));"), std::string::npos) << t;
}

TEST(StepGeometryWriter, LRSurfaceSharedLocalBSplines) {
  ExchangeFile f;
  f.header.schemas = {"TEST"};
  add_lr_spline(f, LRSpline<2>(bilinear()), "lr");
  const std::string t = text(f);
  // Two distinct local B-splines per direction with 1-based indices; the v ones equal the u ones in indices
  // but are separate instances only when knots or degree differ (here: the same), so two in all.
  EXPECT_NE(t.find("#1=LOCAL_B_SPLINE('',1,(1,2),(2,1));"), std::string::npos) << t;
  EXPECT_NE(t.find("LOCAL_B_SPLINE('',1,(1,2),(1,2));"), std::string::npos) << t;
  EXPECT_EQ(t.find("LOCAL_B_SPLINE('',1,(0"), std::string::npos) << t;
  EXPECT_NE(t.find("LOCALLY_REFINED_SPLINE_SURFACE('lr',"), std::string::npos) << t;
  EXPECT_NE(t.find("(1.,1.,1.,1.),.NOT_TESTED.,.LR_B_SPLINE.,.U.,.U.,.U.,((0.,2.),(0.,1.)));"), std::string::npos)
      << t;
}

TEST(StepGeometryWriter, RejectsUnwritable) {
  std::array<KnotVector, 1> kv{KnotVector(1, {0, 0, 1, 1})};
  const TensorSpline<1> c4(kv, 4, false, std::vector<double>(8, 0.0));
  EXPECT_THROW(geometry_exchange_file({c4}, {}), Error);
  EXPECT_THROW(geometry_exchange_file({}, {}), Error);
}

namespace {

// The B-spline on local knots t (size p + 2) at x by the Cox-de Boor recursion, half-open intervals.
double local_bspline(const std::vector<double>& t, double x) {
  const int p = static_cast<int>(t.size()) - 2;
  std::vector<double> N(static_cast<std::size_t>(p) + 1);
  for (int i = 0; i <= p; ++i) N[static_cast<std::size_t>(i)] = t[static_cast<std::size_t>(i)] <= x && x < t[static_cast<std::size_t>(i) + 1] ? 1 : 0;
  for (int q = 1; q <= p; ++q)
    for (int i = 0; i + q <= p; ++i) {
      const auto a = static_cast<std::size_t>(i);
      const double l = t[a + q] > t[a] ? (x - t[a]) / (t[a + q] - t[a]) * N[a] : 0;
      const double r = t[a + q + 1] > t[a + 1] ? (t[a + q + 1] - x) / (t[a + q + 1] - t[a + 1]) * N[a + 1] : 0;
      N[a] = l + r;
    }
  return N[0];
}

// A THB spline with generic coefficients refined at random, its geometry written as HB B-splines and read
// back as the scaled B-splines a Part 42 reader sees: sum_i gamma_i c_i B_i must be the spline.
template <int D>
void check_hierarchical_collection(const std::string& entity) {
  HierarchicalSpline<D> h(test::generic_spline<D>(2, 3, 3, false), HierarchicalBasis::thb);
  test::refine_randomly(h, 3);
  const std::string t = text(geometry_exchange_file({}, {}, {AnyHierarchicalSpline(h)}));
  EXPECT_NE(t.find(".HIERARCHICAL_B_SPLINE."), std::string::npos);
  const ExchangeFile f = parse_exchange_file(t, "hier.stp");
  const GeometryReader reader(f, "hier.stp");
  int found = 0;
  for (const Instance& in : f.instances()) {
    if (in.type_name() != entity) continue;
    ++found;
    LocallyRefinedParts<D> parts;
    if constexpr (D == 2) parts = reader.locally_refined_surface_parts(in);
    else parts = reader.locally_refined_volume_parts(in);
    EXPECT_EQ(parts.type, "HIERARCHICAL_B_SPLINE");
    ASSERT_EQ(static_cast<int>(parts.basis.size()), h.space().num_basis());
    for (const auto& u : test::random_points<D>(50)) {
      double want[3], got[3] = {0, 0, 0};
      h.eval(u, want);
      for (const LRBSpline<D>& b : parts.basis) {
        EXPECT_EQ(b.gamma, 1.0);
        double v = b.gamma;
        for (int k = 0; k < D; ++k) v *= local_bspline(b.knots[static_cast<std::size_t>(k)], u[k]);
        for (int d = 0; d < 3; ++d) got[d] += v * b.coef[static_cast<std::size_t>(d)];
      }
      for (int d = 0; d < 3; ++d) EXPECT_NEAR(got[d], want[d], 1e-12);
    }
  }
  EXPECT_EQ(found, 1);
}

}  // namespace

TEST(StepGeometryWriter, HierarchicalSplinesAsHierarchicalBSplines) {
  check_hierarchical_collection<2>("LOCALLY_REFINED_SPLINE_SURFACE");
  check_hierarchical_collection<3>("LOCALLY_REFINED_SPLINE_VOLUME");
}
