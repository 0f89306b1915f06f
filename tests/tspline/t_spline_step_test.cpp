#include <gtest/gtest.h>

#include <sstream>

#include "trivar/core/error.hpp"
#include "trivar/io/step/step_file.hpp"
#include "trivar/io/step/writer.hpp"
#include "trivar/io/tsm_format.hpp"
#include "trivar/tspline/classification.hpp"
#include "trivar/tspline/t_mesh_builder.hpp"
#include "trivar/tspline/t_spline_surface.hpp"

namespace trivar {
namespace {

using io::step::TSplineStepForm;

TSpline t_junction_spline() {
  std::vector<KnotSegment> g;
  for (int i = 0; i <= 6; ++i) {
    g.push_back({{0.0, double(i)}, {6.0, double(i)}});
    g.push_back({{double(i), 0.0}, {double(i), i == 3 ? 3.0 : 6.0}});
  }
  return t_spline_from_segments({3, 3}, g, [](double s, double t, int a, int b) {
    return RationalPoint{{s + 0.1 * a, t - 0.1 * b, std::cos(s) * std::sin(t) / 3.0}, 1.0 + 0.25 * std::sin(s * t)};
  });
}

std::string to_text(const io::step::ExchangeFile& f) {
  std::ostringstream os;
  io::step::WriteOptions w;
  w.time_stamp = "2026-01-01T00:00:00";
  w.renumber = false;
  io::step::write_exchange_file(os, f, w);
  return os.str();
}

void expect_same_layers(const TSpline& a, const TSpline& b) {
  EXPECT_EQ(a.degrees, b.degrees);
  ASSERT_EQ(a.image.vertices.size(), b.image.vertices.size());
  for (std::size_t i = 0; i < a.image.vertices.size(); ++i) {
    EXPECT_EQ(a.image.vertices[i].s, b.image.vertices[i].s);
    EXPECT_EQ(a.image.vertices[i].t, b.image.vertices[i].t);
    EXPECT_EQ(a.image.vertices[i].links, b.image.vertices[i].links);
  }
  ASSERT_EQ(a.image.edges.size(), b.image.edges.size());
  for (std::size_t i = 0; i < a.image.edges.size(); ++i) {
    EXPECT_EQ(a.image.edges[i].start, b.image.edges[i].start);
    EXPECT_EQ(a.image.edges[i].end, b.image.edges[i].end);
  }
  ASSERT_EQ(a.image.links.size(), b.image.links.size());
  for (std::size_t i = 0; i < a.image.links.size(); ++i) {
    EXPECT_EQ(a.image.links[i].edge, b.image.links[i].edge);
    EXPECT_EQ(a.image.links[i].sense, b.image.links[i].sense);
  }
  ASSERT_EQ(a.image.faces.size(), b.image.faces.size());
  for (std::size_t i = 0; i < a.image.faces.size(); ++i) EXPECT_EQ(a.image.faces[i].loop, b.image.faces[i].loop);
  ASSERT_EQ(a.image.conditions.size(), b.image.conditions.size());
  ASSERT_EQ(a.connect.nodes.size(), b.connect.nodes.size());
  for (std::size_t i = 0; i < a.connect.nodes.size(); ++i) {
    EXPECT_EQ(a.connect.nodes[i].kind, b.connect.nodes[i].kind);
    EXPECT_EQ(a.connect.nodes[i].anchor, b.connect.nodes[i].anchor);
    EXPECT_EQ(a.connect.nodes[i].point, b.connect.nodes[i].point);
    EXPECT_EQ(a.connect.nodes[i].neighbours, b.connect.nodes[i].neighbours);
  }
  ASSERT_EQ(a.pointset.points.size(), b.pointset.points.size());
  for (std::size_t i = 0; i < a.pointset.points.size(); ++i) {
    EXPECT_EQ(a.pointset.points[i].xyz, b.pointset.points[i].xyz);
    EXPECT_EQ(a.pointset.points[i].w, b.pointset.points[i].w);
  }
}

TEST(TSplineStep, SeedEntitiesRoundTripExactly) {
  const TSpline ts = t_junction_spline();
  const std::string text = to_text(io::step::t_spline_exchange_file(ts, TSplineStepForm::t_spline_entities, "tj"));
  EXPECT_NE(text.find("FILE_SCHEMA(('integrated_cnc_schema'))"), std::string::npos);
  EXPECT_NE(text.find("T_NODE_V4("), std::string::npos);
  const io::step::StepContents c = io::step::parse_step(text, "tj.stp");
  ASSERT_EQ(c.t_splines.size(), 1u);
  EXPECT_TRUE(c.lr_splines.empty());
  ASSERT_TRUE(c.t_splines[0].layers.has_value());
  EXPECT_EQ(c.t_splines[0].name, "tj");
  expect_same_layers(ts, *c.t_splines[0].layers);
  // Written again, the file is the same.
  EXPECT_EQ(to_text(io::step::t_spline_exchange_file(*c.t_splines[0].layers, TSplineStepForm::t_spline_entities, "tj")), text);
}

TEST(TSplineStep, Part42FormCarriesTheTypeAndTheSurface) {
  const TSpline ts = t_junction_spline();
  const TSplineSurface surf(ts);
  const std::string text = to_text(io::step::t_spline_exchange_file(ts, TSplineStepForm::part42, "tj"));
  EXPECT_NE(text.find(".ANALYSIS_SUITABLE_T_SPLINE."), std::string::npos);
  EXPECT_NE(text.find("RATIONAL_LOCALLY_REFINED_SPLINE_SURFACE("), std::string::npos);
  const io::step::StepContents c = io::step::parse_step(text, "tj.stp");
  ASSERT_EQ(c.t_splines.size(), 1u);
  EXPECT_EQ(c.t_splines[0].type, "ANALYSIS_SUITABLE_T_SPLINE");
  const TSplineSurface back(c.t_splines[0].degrees, c.t_splines[0].basis);
  for (double s : {0.0, 0.7, 2.9, 3.0, 4.4, 6.0})
    for (double t : {0.0, 1.3, 3.5, 5.9}) {
      double a[9], b[9];
      surf.eval_first_derivatives({s, t}, a);
      back.eval_first_derivatives({s, t}, b);
      for (int d = 0; d < 9; ++d) EXPECT_NEAR(a[d], b[d], 1e-13 * (1 + std::abs(a[d])));
    }
}

TEST(TSplineStep, NonStandardTSplineIsNotReadAsAnLRSpline) {
  // Two crossing T-junction extensions: the blending functions do not sum to one (not an LR spline).
  std::vector<KnotSegment> g;
  for (int i = 0; i <= 6; ++i) {
    g.push_back({{0.0, double(i)}, {6.0, double(i)}});
    g.push_back({{double(i), 0.0}, {double(i), i == 3 ? 3.0 : 6.0}});
  }
  g.push_back({{0.0, 3.5}, {2.0, 3.5}});
  g.push_back({{3.5, 0.0}, {3.5, 6.0}});
  const TSpline ts = t_spline_from_segments({3, 3}, g, [](double s, double t, int, int) {
    return RationalPoint{{s, t, s * t}, 1.0};
  });
  const TSplineSurface surf(ts);
  const TSplineClass cls = classify(ts, surf);
  const std::string text = to_text(io::step::t_spline_exchange_file(ts, TSplineStepForm::part42, ""));
  EXPECT_NE(text.find("." + cls.part42_type() + "."), std::string::npos);
  const io::step::StepContents c = io::step::parse_step(text, "x.stp");
  ASSERT_EQ(c.t_splines.size(), 1u);
  const TSplineSurface back(c.t_splines[0].degrees, c.t_splines[0].basis);
  EXPECT_NEAR(back.partition_of_unity().max_defect, surf.partition_of_unity().max_defect, 1e-12);
}

TEST(TSplineStep, BrokenEntitiesGiveOneLineErrors) {
  const TSpline ts = t_junction_spline();
  std::string text = to_text(io::step::t_spline_exchange_file(ts, TSplineStepForm::t_spline_entities, "tj"));
  // A node pointing at a point that is not in the T-pointset: retarget the first node's point at the image.
  const auto at = text.find("T_NODE_V4('n1',");
  ASSERT_NE(at, std::string::npos);
  const auto comma = text.find(",#", text.find(",#", at) + 1);
  std::string bad = text;
  bad.replace(comma + 2, text.find(',', comma + 1) - comma - 2, "2");
  try {
    io::step::parse_step(bad, "bad.stp");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("T_NODE_V4"), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos);
  }
}

}  // namespace
}  // namespace trivar
