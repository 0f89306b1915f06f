#include "trivar/am/slicer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "am/slicer_test_support.hpp"
#include "trivar/am/dithering.hpp"
#include "trivar/core/error.hpp"
#include "trivar/model/ball.hpp"
#include "trivar/model/cylinder.hpp"
#include "trivar/model/torus.hpp"

using namespace trivar;
using namespace trivar::am;
using trivar::test::glued;
using trivar::test::kResidualBound;

namespace {

// Inside pixels of all layers times the voxel volume.
double sliced_volume(const VModel& m, const SliceOptions& o, SliceSummary* s) {
  *s = slice_model(m, o, LayerConsumer{});
  return static_cast<double>(s->inside_pixels) * (25.4 / o.dpi_x) * (25.4 / o.dpi_y) * o.layer_thickness;
}

}  // namespace

TEST(Slicer, InsidePixelsGiveTheVolumeOfBallAndTorus) {
  SliceOptions o;
  o.dpi_x = o.dpi_y = 300;
  o.layer_thickness = 0.1;
  o.threads = 2;
  SliceSummary s;
  const double R = 3;
  const double ball = sliced_volume(glued(make_ball({R})), o, &s);
  EXPECT_NEAR(ball / (4.0 / 3.0 * std::numbers::pi * R * R * R), 1.0, 0.01);
  EXPECT_LE(s.max_residual, kResidualBound);
  EXPECT_EQ(s.corrected_pixels, 0);
  // Thinner layers: the midpoint rule over z is off by 0.7 % for this tube at 0.1 mm (sqrt profile).
  o.layer_thickness = 0.027;
  const double torus = sliced_volume(glued(make_torus({2.0, 0.6})), o, &s);
  EXPECT_NEAR(torus / (2 * std::numbers::pi * std::numbers::pi * 2.0 * 0.36), 1.0, 0.01);
  EXPECT_LE(s.max_residual, kResidualBound);
}

TEST(Slicer, OneAndTwoThreadsGiveIdenticalLayers) {
  VModel m;
  for (const auto& c : make_ball({2.0})) {
    VCell cell(c);
    cell.set_attribute("material", Attribute::expression({"x * x + y * y + z * z", "1"}, Attribute::Space::model));
    m.add_cell(std::move(cell));
  }
  m.glue();
  SliceOptions o;
  o.dpi_x = 300;
  o.dpi_y = 150;
  o.layer_thickness = 0.2;
  o.z_range = {{-2.0, 2.0}};  // the control box of the rational sphere reaches beyond the radius
  o.threads = 1;
  SliceSummary s1, s2;
  const auto a = slice_model(m, o, &s1);
  o.threads = 2;
  const auto b = slice_model(m, o, &s2);
  ASSERT_EQ(a.size(), b.size());
  ASSERT_EQ(a.size(), 20u);
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].index, static_cast<int>(k));
    EXPECT_EQ(a[k].cell, b[k].cell);
    EXPECT_EQ(a[k].fractions.data(), b[k].fractions.data());
  }
  EXPECT_EQ(s1.inside_pixels, s2.inside_pixels);
  EXPECT_EQ(s1.full_solves, s2.full_solves);
  EXPECT_EQ(s1.max_residual, s2.max_residual);
}

TEST(Slicer, FullSolvesAreRareOnABallAt600Dpi) {
  const VModel m = glued(make_ball({5.0}));
  SliceOptions o;
  o.z_range = {{-0.1, 0.1}};
  o.threads = 2;
  SliceSummary s;
  slice_model(m, o, &s);
  EXPECT_EQ(s.layers, 8);
  EXPECT_GT(s.inside_pixels, 8 * 40000);
  EXPECT_LT(s.full_solve_percent(), 1.0);
  EXPECT_LE(s.max_residual, kResidualBound);
}

TEST(Slicer, ZRangeSelectsTheLayers) {
  const double R = 2;
  const VModel m = glued(make_ball({R}));
  SliceOptions o;
  o.dpi_x = o.dpi_y = 200;
  o.layer_thickness = 0.25;
  o.z_range = {{1.0, 2.0}};
  const auto layers = slice_model(m, o);
  ASSERT_EQ(layers.size(), 4u);
  const double dx = 25.4 / 200;
  for (int k = 0; k < 4; ++k) {
    const SliceLayer& L = layers[static_cast<std::size_t>(k)];
    EXPECT_DOUBLE_EQ(L.z, 1.0 + (k + 0.5) * 0.25);
    // Default raster: the control box minus one pixel; count the centres in the disk independently.
    const double x0 = m.bounding_box().lo[0] - dx, y0 = m.bounding_box().lo[1] - dx;
    const double rho2 = R * R - L.z * L.z;
    long long expected = 0;
    for (int j = 0; j < L.height; ++j)
      for (int i = 0; i < L.width; ++i) {
        const double x = x0 + (i + 0.5) * dx, y = y0 + (j + 0.5) * dx;
        expected += x * x + y * y < rho2 ? 1 : 0;
      }
    EXPECT_EQ(L.stats.inside_pixels, expected) << "layer " << k;
  }
}

TEST(Slicer, ProgressAndSummary) {
  const VModel m = glued(make_ball({1.0}));
  SliceOptions o;
  o.dpi_x = o.dpi_y = 100;
  o.layer_thickness = 0.1;
  o.z_range = {{-1.0, 1.0}};
  o.threads = 2;
  int calls = 0, last = 0, consumed = 0;
  const SliceSummary s = slice_model(
      m, o, [&](SliceLayer&) {
#pragma omp atomic
        ++consumed;
      },
      [&](int done, int total) {
        ++calls;
        EXPECT_EQ(done, last + 1);
        EXPECT_EQ(total, 20);
        last = done;
      });
  EXPECT_EQ(calls, 20);
  EXPECT_EQ(consumed, 20);
  EXPECT_EQ(s.pixels, 20LL * s.width * s.height);
  const std::string line = format_summary(s);
  for (const char* word : {"layers 20", "pixels ", "inside pixels ", "full-solve ", " %", "max residual ", "seconds ",
                           "inside pixels/s "})
    EXPECT_NE(line.find(word), std::string::npos) << word << " in " << line;
}

TEST(Slicer, ErrorsPropagate) {
  const VModel m = glued(make_ball({1.0}));
  SliceOptions o;
  o.layer_thickness = -1;
  EXPECT_THROW(slice_model(m, o), Error);
  o = {};
  o.dpi_x = o.dpi_y = 50;
  o.threads = 2;
  EXPECT_THROW(slice_model(m, o, [](SliceLayer& l) {
                 if (l.index == 3) throw Error("consumer failed");
               }),
               Error);
}

// The material histogram of a dithered slice against the field's integral: a cylinder of radius R whose second
// material grows linearly with the distance from the axis, f2 = r / R, covers 2/3 of every section by
// integral(0..R) (r / R) 2 pi r dr / (pi R^2). Error diffusion conserves material up to a few per cent of the
// perimeter, the pixel sampling of the disc up to its perimeter.
TEST(Slicer, DitheredHistogramMatchesTheFieldIntegral) {
  const double R = 8;
  VModel m;
  for (const auto& c : make_cylinder({.radius = R, .height = 1})) {
    VCell cell(c);
    cell.set_attribute("material", Attribute::expression({"1 - sqrt(x*x + y*y) / 8", "sqrt(x*x + y*y) / 8"},
                                                         Attribute::Space::model));
    m.add_cell(std::move(cell));
  }
  m.glue();
  SliceOptions o;
  o.layer_thickness = 0.25;
  o.z_range = {{0.25, 0.5}};
  const std::vector<SliceLayer> layers = slice_model(m, o);
  ASSERT_EQ(layers.size(), 1u);
  for (DitherMethod method : {DitherMethod::error_diffusion, DitherMethod::ordered}) {
    const LabelImage labels = dither(layers[0].fractions, DitherOptions{method});
    long long counts[3] = {0, 0, 0};
    for (std::size_t p = 0; p < labels.pixel_count(); ++p) ++counts[labels.data()[p]];
    const double inside = static_cast<double>(counts[1] + counts[2]);
    const double perimeter = 2 * std::numbers::pi * R / (25.4 / o.dpi_x);
    EXPECT_NEAR(inside, std::numbers::pi * R * R / std::pow(25.4 / o.dpi_x, 2), 0.5 * perimeter);
    EXPECT_NEAR(static_cast<double>(counts[2]), 2.0 / 3.0 * inside, 0.05 * perimeter) << static_cast<int>(method);
  }
}
