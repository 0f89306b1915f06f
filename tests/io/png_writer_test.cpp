// PNG writer: files read back with libpng's low-level reader (no transformations) give exactly the written
// pixels, palette and transparency; bad input throws and leaves no file behind.
#include <gtest/gtest.h>
#include <png.h>

#include <random>

#include "io/io_test_support.hpp"
#include "support/png_reader.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/png_writer.hpp"

using namespace trivar;
using trivar::test::read_png;

namespace {

MaterialTable three_materials() {
  return MaterialTable({{"rigid", {200, 30, 40, 255}}, {"flexible", {10, 220, 30, 255}}, {"support", {0, 0, 250, 128}}});
}

LabelImage random_labels(int w, int h, int max_label, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> d(0, max_label);
  LabelImage l(w, h);
  for (auto& v : l.data()) v = static_cast<std::uint8_t>(d(rng));
  return l;
}

}  // namespace

TEST(PngWriter, PaletteImageReadsBackExactly) {
  test::TempDir dir;
  const auto materials = three_materials();
  const auto labels = random_labels(37, 23, 3, 1);
  const auto palette = io::material_palette(materials, {255, 255, 255, 0});
  ASSERT_EQ(palette.size(), 4u);
  EXPECT_EQ(palette[0], (Rgba{255, 255, 255, 0}));
  for (int k = 0; k < 3; ++k) EXPECT_EQ(palette[static_cast<std::size_t>(k + 1)], materials[k].colour);

  io::write_palette_png(dir.file("slice.png"), labels, palette);
  io::write_palette_png(dir.file("slice9.png"), labels, palette, 9);
  EXPECT_EQ(read_png(dir.file("slice9.png")).rows, read_png(dir.file("slice.png")).rows);
  const auto f = read_png(dir.file("slice.png"));
  EXPECT_EQ(f.width, 37u);
  EXPECT_EQ(f.height, 23u);
  EXPECT_EQ(f.bit_depth, 8);
  EXPECT_EQ(f.colour_type, PNG_COLOR_TYPE_PALETTE);
  EXPECT_TRUE(f.has_trns);
  EXPECT_EQ(f.palette, palette);
  // PNG row 0 is the top of the picture = the highest y of the layer image.
  for (int r = 0; r < 23; ++r)
    for (int x = 0; x < 37; ++x) ASSERT_EQ(f.rows[static_cast<std::size_t>(r)][static_cast<std::size_t>(x)], labels(x, 22 - r));
}

TEST(PngWriter, OpaquePaletteHasNoTransparencyChunk) {
  test::TempDir dir;
  MaterialTable opaque({{"a", {1, 2, 3, 255}}});
  io::write_palette_png(dir.file("s.png"), random_labels(5, 4, 1, 2), io::material_palette(opaque));
  const auto f = read_png(dir.file("s.png"));
  EXPECT_FALSE(f.has_trns);
  EXPECT_EQ(f.palette, (std::vector<Rgba>{{0, 0, 0, 255}, {1, 2, 3, 255}}));
}

TEST(PngWriter, BitmapPerMaterialReadsBackExactly) {
  test::TempDir dir;
  const auto labels = random_labels(29, 11, 3, 3);  // width not a multiple of 8: padding bits
  for (int label = 1; label <= 3; ++label) {
    const std::string path = dir.file("m" + std::to_string(label) + ".png");
    io::write_bitmap_png(path, labels, label);
    const auto f = read_png(path);
    EXPECT_EQ(f.bit_depth, 1);
    EXPECT_EQ(f.colour_type, PNG_COLOR_TYPE_GRAY);
    for (int r = 0; r < 11; ++r)
      for (int x = 0; x < 29; ++x) {
        const int bit = (f.rows[static_cast<std::size_t>(r)][static_cast<std::size_t>(x / 8)] >> (7 - x % 8)) & 1;
        ASSERT_EQ(bit, labels(x, 10 - r) == label ? 1 : 0) << x << "," << r;
      }
  }
}

TEST(PngWriter, GreyAndColourPreviewsReadBackExactly) {
  test::TempDir dir;
  const int types[] = {PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB, PNG_COLOR_TYPE_RGB_ALPHA};
  for (int c = 1; c <= 4; ++c) {
    LayerImage<std::uint8_t> img(13, 9, c);
    std::mt19937 rng(static_cast<unsigned>(c));
    for (auto& v : img.data()) v = static_cast<std::uint8_t>(rng());
    const std::string path = dir.file("p" + std::to_string(c) + ".png");
    io::write_png(path, img);
    const auto f = read_png(path);
    EXPECT_EQ(f.colour_type, types[c - 1]);
    EXPECT_EQ(f.bit_depth, 8);
    for (int r = 0; r < 9; ++r)
      for (int x = 0; x < 13; ++x)
        for (int k = 0; k < c; ++k)
          ASSERT_EQ(f.rows[static_cast<std::size_t>(r)][static_cast<std::size_t>(x * c + k)], img(x, 8 - r, k));
  }
}

TEST(PngWriter, BadInputThrowsAndWritesNothing) {
  test::TempDir dir;
  const auto path = dir.file("bad.png");
  const std::vector<Rgba> two(2);
  EXPECT_THROW(io::write_palette_png(path, LabelImage(0, 5), two), Error);
  EXPECT_THROW(io::write_palette_png(path, LabelImage(5, 0), two), Error);
  EXPECT_THROW(io::write_palette_png(path, LabelImage(4, 4), std::vector<Rgba>(257)), Error);
  EXPECT_THROW(io::write_palette_png(path, LabelImage(4, 4), std::vector<Rgba>{}), Error);
  EXPECT_THROW(io::write_palette_png(path, random_labels(4, 4, 2, 5), two), Error);  // label 2 beyond palette
  EXPECT_THROW(io::write_bitmap_png(path, LabelImage(0, 0), 1), Error);
  EXPECT_THROW(io::write_bitmap_png(path, LabelImage(3, 3), 256), Error);
  EXPECT_THROW(io::write_bitmap_png(path, LabelImage(3, 3), 1, 10), Error);
  EXPECT_THROW(io::write_palette_png(path, LabelImage(3, 3), two, -1), Error);
  EXPECT_THROW(io::write_png(path, LayerImage<std::uint8_t>(3, 3, 5)), Error);
  EXPECT_THROW(io::write_png(dir.file("no/such/dir/x.png"), LayerImage<std::uint8_t>(3, 3, 1)), Error);
  EXPECT_EQ(dir.entries(), 0);
  // 256 colours is the most a palette holds.
  io::write_palette_png(path, random_labels(16, 16, 255, 6), std::vector<Rgba>(256));
  EXPECT_EQ(read_png(path).palette.size(), 256u);
}
