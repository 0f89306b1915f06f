// Hand-written STEP geometry (tests/data/step/geometry/) against closed forms, and malformed geometry
// failing with "file:line:column: #id: KEYWORD: message".
#include <gtest/gtest.h>

#include <functional>

#include <cmath>
#include <string>

#include "step/step_test_support.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/step/step_file.hpp"

using namespace trivar;
using namespace trivar::io::step;

namespace {

std::string geo(const std::string& name) { return trivar::test::step_data("geometry/" + name); }

template <int D>
const TensorSpline<D>& as(const AnySpline& s) {
  return std::get<TensorSpline<D>>(s);
}

// The message of the Error that parse_step throws on the data section `data` (file "bad.stp").
std::string failure(const std::string& data) {
  try {
    parse_step(trivar::test::step_file(data), "bad.stp");
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(StepGeometryReader, BilinearPatch) {
  const auto c = read_step(geo("bilinear_patch.stp"));
  ASSERT_EQ(c.splines.size(), 1u);
  EXPECT_EQ(c.spline_info[0].name, "patch");
  EXPECT_EQ(c.spline_info[0].id, 10u);
  EXPECT_EQ(c.spline_info[0].kind, GeometryKind::surface);
  const auto& s = as<2>(c.splines[0]);
  EXPECT_FALSE(s.is_rational());
  for (double u : {0.0, 0.3, 1.1, 2.0})
    for (double v : {0.0, 0.25, 0.9, 1.0}) {
      double x[3];
      s.eval({u, v}, x);
      EXPECT_NEAR(x[0], u / 2, 1e-15);
      EXPECT_NEAR(x[1], v, 1e-15);
      EXPECT_NEAR(x[2], u * v / 2, 1e-15);
    }
  EXPECT_EQ(c.entities.at("CARTESIAN_POINT").kept, 4u);
}

TEST(StepGeometryReader, RationalQuarterCircle) {
  const auto c = read_step(geo("quarter_circle.stp"));
  ASSERT_EQ(c.splines.size(), 1u);
  EXPECT_EQ(c.spline_info[0].name, "arc");
  const auto& s = as<1>(c.splines[0]);
  EXPECT_TRUE(s.is_rational());
  for (int i = 0; i <= 50; ++i) {
    double x[3];
    s.eval({1.5707963267948966 * i / 50}, x);
    EXPECT_NEAR(std::hypot(x[0] - 1.0, x[1]), 2.0, 1e-14);
    EXPECT_EQ(x[2], 0.0);
    EXPECT_GE(x[0], 1.0 - 1e-15);
    EXPECT_GE(x[1], -1e-15);
  }
}

TEST(StepGeometryReader, ImpliedKnotForms) {
  const auto c = read_step(geo("curve_forms.stp"));
  ASSERT_EQ(c.splines.size(), 4u);
  const char* names[] = {"bezier", "quasi", "uniform", "uniform complex"};
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(c.spline_info[i].name, names[i]);
    const auto& s = as<1>(c.splines[i]);
    EXPECT_EQ(s.domain().lo[0], 0.0);
    EXPECT_EQ(s.domain().hi[0], 2.0);
    for (int j = 0; j <= 40; ++j) {
      const double u = 2.0 * j / 40;
      double x[3];
      s.eval({u}, x);
      EXPECT_NEAR(x[0], u, 1e-14) << names[i];
      EXPECT_NEAR(x[1], u * u, 1e-14) << names[i];
    }
  }
  EXPECT_EQ(as<1>(c.splines[0]).knots(0).knots(), (std::vector<double>{0, 0, 0, 1, 1, 2, 2, 2}));
  EXPECT_EQ(as<1>(c.splines[1]).knots(0).knots(), (std::vector<double>{0, 0, 0, 1, 2, 2, 2}));
  EXPECT_EQ(as<1>(c.splines[2]).knots(0).knots(), (std::vector<double>{-2, -1, 0, 1, 2, 3, 4}));
}

TEST(StepGeometryReader, VolumeForms) {
  const auto c = read_step(geo("volume_forms.stp"));
  ASSERT_EQ(c.splines.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    const auto& s = as<3>(c.splines[i]);
    EXPECT_EQ(s.is_rational(), i == 3);
    for (double u : {0.0, 0.2, 0.7, 1.0})
      for (double v : {0.0, 0.4, 1.0})
        for (double w : {0.0, 0.6, 1.0}) {
          double x[3];
          s.eval({u, v, w}, x);
          // Independent trilinear rational formula; weights w_ijk from the file, points (i, j, k).
          double num[3] = {0, 0, 0}, den = 0;
          for (int a = 0; a < 2; ++a)
            for (int b = 0; b < 2; ++b)
              for (int g = 0; g < 2; ++g) {
                const double wt = (i == 3 && a == 1 && (b + g) == 1) ? 0.5 : 1.0;
                const double B = (a ? u : 1 - u) * (b ? v : 1 - v) * (g ? w : 1 - w) * wt;
                num[0] += B * a;
                num[1] += B * b;
                num[2] += B * g;
                den += B;
              }
          for (int d = 0; d < 3; ++d) EXPECT_NEAR(x[d], num[d] / den, 1e-15) << i;
        }
  }
  EXPECT_EQ(c.entities.at("REPRESENTATION").skipped, 1u);
}

TEST(StepGeometryReader, LRSurfaceBothIndexBases) {
  for (const char* f : {"lr_surface_1based.stp", "lr_surface_0based.stp", "lr_surface_rational.stp"}) {
    const auto c = read_step(geo(f));
    ASSERT_EQ(c.lr_splines.size(), 1u) << f;
    EXPECT_EQ(c.lr_info[0].kind, GeometryKind::lr_surface);
    const auto& s = std::get<LRSpline<2>>(c.lr_splines[0]);
    const bool rational = std::string(f).find("rational") != std::string::npos;
    EXPECT_EQ(s.is_rational(), rational);
    EXPECT_EQ(s.num_basis(), 4);
    for (double u : {0.0, 0.3, 0.8, 1.0})
      for (double v : {0.0, 0.5, 1.7, 2.0}) {
        double x[3];
        s.eval({u, v}, x);
        // Bilinear hats; weights (1, 2, 1, 1) on P00, P10, P01, P11 for the rational file.
        const double N[4] = {(1 - u) * (1 - v / 2), u * (1 - v / 2), (1 - u) * v / 2, u * v / 2};
        const double w[4] = {1, rational ? 2.0 : 1.0, 1, 1};
        const double P[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 2, 0}, {1, 2, 3}};
        double den = 0, num[3] = {0, 0, 0};
        for (int i = 0; i < 4; ++i) {
          den += w[i] * N[i];
          for (int d = 0; d < 3; ++d) num[d] += w[i] * N[i] * P[i][d];
        }
        for (int d = 0; d < 3; ++d) EXPECT_NEAR(x[d], num[d] / den, 1e-15) << f;
      }
  }
}

TEST(StepGeometryReader, LRVolumeComplex) {
  const auto c = read_step(geo("lr_volume.stp"));
  ASSERT_EQ(c.lr_splines.size(), 1u);
  EXPECT_EQ(c.lr_info[0].name, "vol");
  const auto& s = std::get<LRSpline<3>>(c.lr_splines[0]);
  EXPECT_EQ(s.num_basis(), 8);
  for (double u : {0.0, 0.3, 1.0})
    for (double v : {0.1, 0.9})
      for (double w : {0.0, 0.45, 1.0}) {
        double x[3];
        s.eval({u, v, w}, x);
        EXPECT_NEAR(x[0], u, 1e-15);
        EXPECT_NEAR(x[1], v, 1e-15);
        EXPECT_NEAR(x[2], w, 1e-15);
      }
}

// A realistic AP214 export: B-spline surfaces with their faces, curves with their edges, statistics.
TEST(StepGeometryReader, CadFileExtraction) {
  const auto c = read_step(geo("cad_part_ap214.stp"));
  EXPECT_EQ(c.header.schemas.at(0), "AUTOMOTIVE_DESIGN { 1 0 10303 214 3 1 1 }");
  EXPECT_EQ(c.instance_count(), 68u);  // grep -c '^#' of the file
  ASSERT_EQ(c.splines.size(), 5u);
  // File order: #110 surface, #210 rational surface, #411, #422 curves, #425 2-D pcurve.
  const std::uint64_t ids[] = {110, 210, 411, 422, 425};
  for (std::size_t i = 0; i < 5; ++i) EXPECT_EQ(c.spline_info[i].id, ids[i]);
  EXPECT_EQ(c.spline_info[0].faces, (std::vector<std::uint64_t>{100}));
  EXPECT_EQ(c.spline_info[1].faces, (std::vector<std::uint64_t>{200}));
  EXPECT_EQ(c.spline_info[1].name, "cyl");
  EXPECT_EQ(c.spline_info[1].entity,
            "BOUNDED_SURFACE+B_SPLINE_SURFACE+B_SPLINE_SURFACE_WITH_KNOTS+GEOMETRIC_REPRESENTATION_ITEM+"
            "RATIONAL_B_SPLINE_SURFACE+REPRESENTATION_ITEM+SURFACE");
  EXPECT_EQ(c.spline_info[2].edges, (std::vector<std::uint64_t>{410}));
  EXPECT_EQ(c.spline_info[3].edges, (std::vector<std::uint64_t>{420}));  // through SURFACE_CURVE #421
  EXPECT_TRUE(c.spline_info[4].edges.empty());
  EXPECT_EQ(std::visit([](const auto& s) { return s.dim(); }, c.splines[4]), 2);
  // The quarter cylinder: radius 10 about the line x = 10, z = 0 (weight written with 15 digits).
  const auto& cyl = std::get<TensorSpline<2>>(c.splines[1]);
  for (double u : {0.0, 0.4, 1.2, 1.5707963267949})
    for (double v : {0.0, 2.5, 5.0}) {
      double x[3];
      cyl.eval({u, v}, x);
      EXPECT_NEAR(std::hypot(x[0] - 10.0, x[2]), 10.0, 1e-12);
      EXPECT_NEAR(x[1], v, 1e-14);
    }
  // Statistics, counted by hand from the file.
  const auto count = [&](const std::string& k) { return c.entities.count(k) ? c.entities.at(k) : EntityCount{}; };
  EXPECT_EQ(count("CARTESIAN_POINT").kept, 15u);
  EXPECT_EQ(count("B_SPLINE_CURVE_WITH_KNOTS").kept, 3u);
  EXPECT_EQ(count("ADVANCED_FACE").kept, 3u);
  EXPECT_EQ(count("EDGE_CURVE").kept, 3u);
  EXPECT_EQ(count("ORIENTED_EDGE").skipped, 4u);
  EXPECT_EQ(count("FACE_OUTER_BOUND").skipped, 3u);
  EXPECT_EQ(count("EDGE_LOOP").skipped, 3u);
  EXPECT_EQ(count("VERTEX_POINT").skipped, 2u);
  EXPECT_EQ(count("AXIS2_PLACEMENT_3D").skipped, 2u);
  EXPECT_EQ(count("PLANE").skipped, 1u);
  EXPECT_EQ(count("LINE").skipped, 1u);
  EXPECT_EQ(count("MANIFOLD_SOLID_BREP").skipped, 1u);
  EXPECT_EQ(count("CLOSED_SHELL").skipped, 1u);
  EXPECT_EQ(count("PRODUCT").skipped, 1u);
  EXPECT_EQ(count("SHAPE_DEFINITION_REPRESENTATION").skipped, 1u);
  EXPECT_EQ(count("LENGTH_UNIT+NAMED_UNIT+SI_UNIT").skipped, 1u);
}

TEST(StepGeometryReader, MalformedGeometry) {
  const std::string pts =
      "#1=CARTESIAN_POINT('',(0.,0.,0.));#2=CARTESIAN_POINT('',(1.,0.,0.));#3=CARTESIAN_POINT('',(2.,1.,0.));\n";
  // Data starts on line 8 of trivar::test::step_file; the spline is on line 9.
  const auto expect = [](const std::string& data, const std::string& prefix, const std::string& part) {
    const std::string m = failure(data);
    EXPECT_EQ(m.rfind(prefix, 0), 0u) << m;
    EXPECT_NE(m.find(part), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  };
  const std::string curve = "bad.stp:9:1: #4: B_SPLINE_CURVE_WITH_KNOTS: ";
  expect(pts + "#4=B_SPLINE_CURVE_WITH_KNOTS('',2,(#1,#2,#3),.UNSPECIFIED.,.F.,.F.,(3,2),(0.,1.),.UNSPECIFIED.);",
         curve, "multiplicities sum to 5, expected 6");
  expect(pts + "#4=B_SPLINE_CURVE_WITH_KNOTS('',2,(#1,#2,#3),.UNSPECIFIED.,.F.,.F.,(3,3),(1.,1.),.UNSPECIFIED.);",
         curve, "not strictly increasing");
  expect(pts + "#4=B_SPLINE_CURVE_WITH_KNOTS('',1,(#1,#2,#3),.UNSPECIFIED.,.F.,.F.,(1,2,2),(0.,1.,2.),.UNSPECIFIED.);",
         curve, "multiplicity 2 of knot 1 outside 1..1");
  expect(pts + "#4=B_SPLINE_CURVE_WITH_KNOTS('',2,(#1,#2,#5),.UNSPECIFIED.,.F.,.F.,(3,3),(0.,1.),.UNSPECIFIED.);"
               "#5=DIRECTION('',(1.,0.,0.));",
         curve, "control point 2: #5 is not a CARTESIAN_POINT");
  expect(pts + "#4=B_SPLINE_CURVE_WITH_KNOTS('',2,(#1,#2,#9),.UNSPECIFIED.,.F.,.F.,(3,3),(0.,1.),.UNSPECIFIED.);",
         "bad.stp:9:1: #4: B_SPLINE_CURVE_WITH_KNOTS refers to undefined instance #9", "");
  expect(pts + "#4=(BOUNDED_CURVE()B_SPLINE_CURVE(2,(#1,#2,#3),.UNSPECIFIED.,.F.,.F.)"
               "B_SPLINE_CURVE_WITH_KNOTS((3,3),(0.,1.),.UNSPECIFIED.)CURVE()GEOMETRIC_REPRESENTATION_ITEM()"
               "RATIONAL_B_SPLINE_CURVE((1.,0.,1.))REPRESENTATION_ITEM(''));",
         "bad.stp:9:1: #4: BOUNDED_CURVE+B_SPLINE_CURVE+", "weights_data 1: weight 0.000000 is not positive");
  expect(pts + "#4=B_SPLINE_SURFACE_WITH_KNOTS('',1,1,((#1,#2),(#3)),.UNSPECIFIED.,.F.,.F.,.F.,"
               "(2,2),(2,2),(0.,1.),(0.,1.),.UNSPECIFIED.);",
         "bad.stp:9:1: #4: B_SPLINE_SURFACE_WITH_KNOTS: ", "control_points_list[1]: 1 entries, expected 2");
  expect(pts + "#4=B_SPLINE_VOLUME_WITH_KNOTS('',1,1,1,(((#1,#2),(#3,#1)),((#1,#2),(#3,#1))),"
               "(2,2),(2,2),(2,2),(0.,1.),(0.,1.),(0.,1.),.UNSPECIFIED.);",
         "bad.stp:9:1: #4: B_SPLINE_VOLUME_WITH_KNOTS: ", "12 parameters, expected 11");
  // Curve where a point is expected is a type error; a point where a B-spline is expected likewise.
  expect(pts + "#4=LOCAL_B_SPLINE('',1,(1,2),(2,1));#5=LOCAL_B_SPLINE('',1,(1,2),(1,2));\n"
               "#6=LOCALLY_REFINED_SPLINE_SURFACE('',(#4,#5,#4,#1),(#4,#4,#5,#5),(0.,1.),(0.,1.),(#1,#2,#3,#1),"
               "(1.,1.,1.,1.),.NOT_TESTED.,.LR_B_SPLINE.,.F.,.F.,.F.,((0.,1.),(0.,1.)));",
         "bad.stp:10:1: #6: LOCALLY_REFINED_SPLINE_SURFACE: ",
         "u_b_splines[3]: #1 is a CARTESIAN_POINT, expected a LOCAL_B_SPLINE");
  expect(pts + "#4=LOCAL_B_SPLINE('',1,(1,2),(2,1));#5=LOCAL_B_SPLINE('',1,(1,2),(1,2));\n"
               "#6=LOCALLY_REFINED_SPLINE_SURFACE('',(#4,#5,#4,#5),(#4,#4,#5,#5),(0.,1.),(0.,1.),(#1,#2,#3,#1),"
               "(1.,1.5,1.,1.),.NOT_TESTED.,.LR_B_SPLINE.,.F.,.F.,.F.,((0.,1.),(0.,1.)));",
         "bad.stp:10:1: #6: LOCALLY_REFINED_SPLINE_SURFACE: ", "scaling_factors[1]: 1.500000 outside (0, 1]");
  expect(pts + "#4=LOCAL_B_SPLINE('',1,(1,2),(2,2));#5=LOCAL_B_SPLINE('',1,(1,2),(1,2));\n"
               "#6=LOCALLY_REFINED_SPLINE_SURFACE('',(#4,#5,#4,#5),(#4,#4,#5,#5),(0.,1.),(0.,1.),(#1,#2,#3,#1),"
               "(1.,1.,1.,1.),.NOT_TESTED.,.LR_B_SPLINE.,.F.,.F.,.F.,((0.,1.),(0.,1.)));",
         "bad.stp:10:1: #6: LOCALLY_REFINED_SPLINE_SURFACE: ", "multiplicities sum to 4, expected degree + 2 = 3");
  expect(pts + "#4=LOCAL_B_SPLINE('',1,(1,2),(2,1));#5=LOCAL_B_SPLINE('',1,(1,2),(1,2));\n"
               "#6=LOCALLY_REFINED_SPLINE_SURFACE('',(#4,#5,#4,#5),(#4,#4,#5,#5),(0.,1.),(0.,1.),(#1,#2,#3,#1),"
               "(1.,1.,1.,1.),.NOT_TESTED.,.LR_B_SPLINE.,.F.,.F.,.F.,((0.,1.),(0.,3.)));",
         "bad.stp:10:1: #6: LOCALLY_REFINED_SPLINE_SURFACE: ", "domain[1]");
}

TEST(StepGeometryReader, UnknownEntitiesAreCounted) {
  const auto c = parse_step(trivar::test::step_file("#1=WIDGET('',3);#2=(FOO(1)BAR(.X.));#3=!USER(#1);"), "u.stp");
  EXPECT_TRUE(c.splines.empty());
  EXPECT_EQ(c.entities.at("WIDGET").skipped, 1u);
  EXPECT_EQ(c.instance_count(), 3u);
}

// Quadratic LR curve on knots 0, 1, 2, 3 with a double knot at 2 and one B-spline halved (gamma 0.5) twice
// over, so coefficients add up: f(t) = sum gamma_i c_i B_i(t), checked against B-splines evaluated here by the
// Cox-de Boor recursion, independently of trivar's basis code; indices 1-based.
TEST(StepGeometryReader, LRCurvesBecomeExactBSplineCurves) {
  const auto c = parse_step(trivar::test::step_file(
      "#1=CARTESIAN_POINT('',(0.,0.));#2=CARTESIAN_POINT('',(1.,2.));#3=CARTESIAN_POINT('',(3.,-1.));"
      "#4=CARTESIAN_POINT('',(4.,1.));"
      "#11=LOCAL_B_SPLINE('',2,(1,2,3,4),(1,1,1,1));#12=LOCAL_B_SPLINE('',2,(2,3,4),(1,1,2));"
      "#13=LOCAL_B_SPLINE('',2,(3,4),(2,2));"
      "#5=LOCALLY_REFINED_SPLINE_CURVE('c',(#11,#12,#12,#13),(0.,1.,2.,3.),(#1,#2,#3,#4),(1.,0.5,0.5,1.),.F.,"
      ".LR_B_SPLINE.,.F.,(0.,3.));"));
  ASSERT_EQ(c.splines.size(), 1u);
  EXPECT_TRUE(c.lr_splines.empty());
  EXPECT_EQ(c.spline_info[0].kind, GeometryKind::lr_curve);
  EXPECT_EQ(c.spline_info[0].name, "c");
  const auto& curve = std::get<trivar::TensorSpline<1>>(c.splines[0]);
  // Cox-de Boor on a local knot vector.
  std::function<double(const std::vector<double>&, int, double)> B = [&](const std::vector<double>& t, int p, double x) {
    if (p == 0) return (t[0] <= x && x < t[1]) || (x == t[1] && x == 3.0 && t[0] < t[1]) ? 1.0 : 0.0;
    double v = 0;
    if (t[p] > t[0]) v += (x - t[0]) / (t[p] - t[0]) * B({t.begin(), t.end() - 1}, p - 1, x);
    if (t[p + 1] > t[1]) v += (t[p + 1] - x) / (t[p + 1] - t[1]) * B({t.begin() + 1, t.end()}, p - 1, x);
    return v;
  };
  const std::vector<std::vector<double>> knots = {{0, 1, 2, 3}, {1, 2, 3, 3}, {1, 2, 3, 3}, {2, 2, 3, 3}};
  const double gamma[4] = {1, 0.5, 0.5, 1}, cp[4][2] = {{0, 0}, {1, 2}, {3, -1}, {4, 1}};
  for (double x = 0; x <= 3.0; x += 0.125) {
    double expected[2] = {0, 0}, got[2];
    for (int i = 0; i < 4; ++i)
      for (int d = 0; d < 2; ++d) expected[d] += gamma[i] * cp[i][d] * B(knots[i], 2, x);
    curve.eval({x}, got);
    EXPECT_NEAR(got[0], expected[0], 1e-14) << x;
    EXPECT_NEAR(got[1], expected[1], 1e-14) << x;
  }
}

// The rational form: a quarter of the unit circle as three Bezier B-splines with weights 1, sqrt(2)/2, 1.
TEST(StepGeometryReader, RationalLRCurveIsAnExactArc) {
  const auto c = parse_step(trivar::test::step_file(
      "#1=CARTESIAN_POINT('',(1.,0.));#2=CARTESIAN_POINT('',(1.,1.));#3=CARTESIAN_POINT('',(0.,1.));"
      "#11=LOCAL_B_SPLINE('',2,(1,2),(3,1));#12=LOCAL_B_SPLINE('',2,(1,2),(2,2));#13=LOCAL_B_SPLINE('',2,(1,2),(1,3));"
      "#5=RATIONAL_LOCALLY_REFINED_SPLINE_CURVE('arc',(#11,#12,#13),(0.,1.),(#1,#2,#3),(1.,1.,1.),.F.,"
      ".LR_B_SPLINE.,.F.,(0.,1.),(1.,0.70710678118654757,1.));"));
  ASSERT_EQ(c.splines.size(), 1u);
  const auto& arc = std::get<trivar::TensorSpline<1>>(c.splines[0]);
  EXPECT_TRUE(arc.is_rational());
  for (double t = 0; t <= 1.0; t += 0.0625) {
    double x[2];
    arc.eval({t}, x);
    EXPECT_NEAR(std::hypot(x[0], x[1]), 1.0, 1e-15) << t;
  }
}
