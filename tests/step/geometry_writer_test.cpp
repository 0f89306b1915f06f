// The STEP text trivar writes for its objects: entities, the AP242 context, 1-based shared LOCAL_B_SPLINEs.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "trivar/core/error.hpp"
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
