// Dithering: material conservation, purity, monotone density along a gradient, exact ordered tiles,
// empty outside pixels and determinism. Reference values come from the input fractions (exact counts).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

#include "trivar/am/dithering.hpp"
#include "trivar/core/error.hpp"
#include "trivar/core/parallel.hpp"

using namespace trivar;
using namespace trivar::am;

namespace {

FractionImage constant(int w, int h, const std::vector<float>& f) {
  FractionImage img(w, h, static_cast<int>(f.size()));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) std::copy(f.begin(), f.end(), img.pixel(x, y));
  return img;
}

// Fractions f inside the disc of radius r centred in the image, zero (outside) elsewhere.
FractionImage disc(int w, int h, double r, const std::vector<float>& f) {
  FractionImage img(w, h, static_cast<int>(f.size()));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (std::hypot(x + 0.5 - w / 2.0, y + 0.5 - h / 2.0) < r) std::copy(f.begin(), f.end(), img.pixel(x, y));
  return img;
}

std::vector<long> histogram(const LabelImage& l, int materials) {
  std::vector<long> h(static_cast<std::size_t>(materials + 1), 0);
  for (auto v : l.data()) ++h.at(v);
  return h;
}

const DitherOptions diffusion{DitherMethod::error_diffusion, 16};
const DitherOptions ordered8{DitherMethod::ordered, 8};
const DitherOptions ordered16{DitherMethod::ordered, 16};

}  // namespace

TEST(Dithering, ErrorDiffusionConservesMaterialOnARectangle) {
  // On a full rectangle only the last pixel has no neighbour ahead, so counts equal N * f up to its residual.
  for (const std::vector<float>& f : {std::vector<float>{0.25f, 0.75f}, std::vector<float>{1 / 3.f, 1 / 3.f, 1 / 3.f},
                                      std::vector<float>{0.1f, 0.2f, 0.3f, 0.4f}}) {
    const int w = 401, h = 297;
    const auto l = dither(constant(w, h, f), diffusion);
    const auto hist = histogram(l, static_cast<int>(f.size()));
    EXPECT_EQ(hist[0], 0);
    double sum = 0;
    for (float v : f) sum += v;
    for (std::size_t k = 0; k < f.size(); ++k)
      EXPECT_NEAR(static_cast<double>(hist[k + 1]), w * h * f[k] / sum, 2.0) << "material " << k;
  }
}

TEST(Dithering, ErrorDiffusionOnADiscIsExactToThePerimeter) {
  const int w = 420, h = 400;
  const double r = 180;
  const auto in = disc(w, h, r, {0.3f, 0.7f});
  const auto l = dither(in, diffusion);
  long inside = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const bool is_in = in(x, y, 0) > 0;
      inside += is_in;
      EXPECT_EQ(l(x, y) != empty_label, is_in) << x << "," << y;
    }
  const auto hist = histogram(l, 2);
  const double perimeter = 2 * std::numbers::pi * r;
  EXPECT_NEAR(static_cast<double>(hist[1]), 0.3 * static_cast<double>(inside), 0.02 * perimeter);
  EXPECT_NEAR(static_cast<double>(hist[2]), 0.7 * static_cast<double>(inside), 0.02 * perimeter);
}

TEST(Dithering, PureMaterialGivesOnlyThatMaterial) {
  for (const auto& opt : {diffusion, ordered8, ordered16}) {
    // Unnormalised and negative inputs: clamping to [0, 1] leaves material 1 alone.
    const auto l = dither(constant(64, 48, {-0.5f, 7.0f, 0.0f}), opt);
    for (auto v : l.data()) ASSERT_EQ(v, 2);
    const auto d = dither(disc(64, 48, 20, {0, 0, 1}), opt);
    const auto hist = histogram(d, 3);
    EXPECT_EQ(hist[1] + hist[2], 0);
    EXPECT_GT(hist[3], 0);
  }
}

TEST(Dithering, LinearGradientGivesMonotoneLocalDensity) {
  // Material 0 goes linearly from 0 at the left to 1 at the right; the density in 32-column blocks must follow
  // the block mean of the fraction and grow from block to block.
  const int w = 512, h = 128, block = 32;
  FractionImage in(w, h, 2);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float f = static_cast<float>(x) / static_cast<float>(w - 1);
      in(x, y, 0) = f;
      in(x, y, 1) = 1 - f;
    }
  for (const auto& opt : {diffusion, ordered8, ordered16}) {
    const auto l = dither(in, opt);
    double previous = -1;
    for (int b = 0; b < w / block; ++b) {
      long count = 0;
      double expected = 0;
      for (int y = 0; y < h; ++y)
        for (int x = b * block; x < (b + 1) * block; ++x) {
          count += l(x, y) == 1;
          expected += in(x, y, 0);
        }
      const double density = static_cast<double>(count) / (block * h);
      EXPECT_NEAR(density, expected / (block * h), 0.02) << "block " << b;
      EXPECT_GT(density, previous) << "block " << b;
      previous = density;
    }
  }
}

TEST(Dithering, OrderedTilesAreExact) {
  // Thresholds (B + 1/2) / n^2 take every value k / n^2 + 1/(2 n^2) once per tile, so a fraction that is a
  // multiple of 1 / n^2 is met exactly on each n x n tile.
  for (int n : {2, 4, 8, 16}) {
    const auto l = dither(constant(n, n, {0.5f, 0.5f}), {DitherMethod::ordered, n});
    const auto hist = histogram(l, 2);
    EXPECT_EQ(hist[1], n * n / 2);
    EXPECT_EQ(hist[2], n * n / 2);
  }
  const auto l = dither(constant(48, 32, {0.25f, 0.25f, 0.5f}), ordered16);
  for (int ty = 0; ty < 2; ++ty)
    for (int tx = 0; tx < 3; ++tx) {
      int count[4] = {0, 0, 0, 0};
      for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) ++count[l(16 * tx + x, 16 * ty + y)];
      EXPECT_EQ(count[1], 64);
      EXPECT_EQ(count[2], 64);
      EXPECT_EQ(count[3], 128);
    }
}

TEST(Dithering, BayerMatricesArePermutationsWithTheRecursiveLayout) {
  const int* b2 = bayer_matrix(2);
  EXPECT_EQ(std::vector<int>(b2, b2 + 4), (std::vector<int>{0, 2, 3, 1}));
  for (int n : {2, 4, 8, 16}) {
    const int* b = bayer_matrix(n);
    std::vector<int> v(b, b + n * n);
    std::sort(v.begin(), v.end());
    for (int i = 0; i < n * n; ++i) ASSERT_EQ(v[static_cast<std::size_t>(i)], i);
  }
  // Every 2 x 2 block of the 4 x 4 matrix holds one value of each residue mod 4 in the 2 x 2 pattern order.
  const int* b4 = bayer_matrix(4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) EXPECT_EQ(b4[y * 4 + x] / 4, b2[(y % 2) * 2 + x % 2]);
}

TEST(Dithering, OutsidePixelsStayEmptyForBothMethods) {
  const auto in = disc(97, 83, 30, {0.2f, 0.3f, 0.5f});
  for (const auto& opt : {diffusion, ordered16}) {
    const auto l = dither(in, opt);
    for (int y = 0; y < 83; ++y)
      for (int x = 0; x < 97; ++x) ASSERT_EQ(l(x, y) == empty_label, in(x, y, 0) == 0) << x << "," << y;
  }
}

TEST(Dithering, IsDeterministicAndIndependentOfThreadCount) {
  std::vector<FractionImage> layers;
  for (int z = 0; z < 6; ++z) {
    FractionImage in(131, 77, 3);
    for (int y = 0; y < 77; ++y)
      for (int x = 0; x < 131; ++x) {
        in(x, y, 0) = static_cast<float>(0.5 + 0.5 * std::sin(0.05 * x + z));
        in(x, y, 1) = static_cast<float>(0.5 + 0.5 * std::cos(0.07 * y));
        in(x, y, 2) = 0.3f;
      }
    layers.push_back(std::move(in));
  }
  for (const auto& opt : {diffusion, ordered8}) {
    std::vector<LabelImage> one(layers.size()), two(layers.size());
    parallel_for(static_cast<std::ptrdiff_t>(layers.size()), 1,
                 [&](std::ptrdiff_t i) { dither(layers[static_cast<std::size_t>(i)], one[static_cast<std::size_t>(i)], opt); });
    parallel_for(static_cast<std::ptrdiff_t>(layers.size()), 2,
                 [&](std::ptrdiff_t i) { two[static_cast<std::size_t>(i)] = dither(layers[static_cast<std::size_t>(i)], opt); });
    for (std::size_t i = 0; i < layers.size(); ++i) EXPECT_EQ(one[i].data(), two[i].data()) << "layer " << i;
  }
}

TEST(Dithering, BadInputThrows) {
  auto in = constant(8, 8, {0.5f, 0.5f});
  in(3, 4, 1) = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(dither(in, diffusion), Error);
  EXPECT_THROW(dither(in, ordered8), Error);
  EXPECT_THROW(dither(constant(4, 4, {0.5f, 0.5f}), {DitherMethod::ordered, 3}), Error);
  EXPECT_THROW(dither(FractionImage(2, 2, 256)), Error);
  EXPECT_THROW(bayer_matrix(32), Error);
  // An empty image is valid and gives an empty label image.
  EXPECT_EQ(dither(FractionImage(0, 0, 2)).pixel_count(), 0u);
}
