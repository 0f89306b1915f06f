// Bitmap font: known glyphs have their pixels, drawn text is exactly the glyph bits blown up by the scale inside
// its box (found here by the inverse mapping from pixel to glyph bit), the vertical direction is the
// horizontal drawing turned a quarter counter-clockwise, and clipping keeps the visible part unchanged.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>

#include "trivar/core/error.hpp"
#include "trivar/io/bitmap_font.hpp"

using namespace trivar;
using Image = LayerImage<std::uint8_t>;

namespace {

constexpr io::Rgb white{255, 255, 255}, red{200, 10, 20};

io::Rgb at(const Image& img, int x, int y) {
  const std::uint8_t* p = img.pixel(x, y);
  return {p[0], p[1], p[2]};
}

// Whether `text` drawn upright with its lower-left corner at the origin inks the offset (u, v) of its box.
bool inked(std::string_view text, int scale, int u, int v) {
  if (u < 0 || v < 0 || u >= io::text_width(text, scale) || v >= io::glyph_height * scale) return false;
  const int cell = u / scale, col = cell % io::glyph_advance, row = io::glyph_height - 1 - v / scale;
  const char c = text[static_cast<std::size_t>(cell / io::glyph_advance)];
  return col < io::glyph_width && ((io::glyph(c)[static_cast<std::size_t>(row)] >> (io::glyph_width - 1 - col)) & 1);
}

}  // namespace

TEST(BitmapFont, KnownGlyphs) {
  using Rows = std::array<std::uint8_t, io::glyph_height>;
  EXPECT_EQ(io::glyph('A'), (Rows{0x0E, 0x11, 0x11, 0x11, 0x1F, 0x11, 0x11}));
  EXPECT_EQ(io::glyph('0'), (Rows{0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}));
  EXPECT_EQ(io::glyph('-'), (Rows{0, 0, 0, 0x1F, 0, 0, 0}));
  EXPECT_EQ(io::glyph(' '), Rows{});
  // Outside printable ASCII: the question mark.
  EXPECT_EQ(io::glyph('\n'), io::glyph('?'));
  EXPECT_EQ(io::glyph('\x7f'), io::glyph('?'));
  EXPECT_EQ(io::glyph(static_cast<char>(200)), io::glyph('?'));
  // Every printable character but the space has ink within 5 columns, and no two share a shape.
  std::set<Rows> shapes;
  for (int c = 33; c <= 126; ++c) {
    const Rows& g = io::glyph(static_cast<char>(c));
    int ink = 0;
    for (auto r : g) {
      EXPECT_LT(r, 1 << io::glyph_width) << static_cast<char>(c);
      ink |= r;
    }
    EXPECT_NE(ink, 0) << static_cast<char>(c);
    shapes.insert(g);
  }
  EXPECT_EQ(shapes.size(), 94u);
}

TEST(BitmapFont, TextIsTheScaledGlyphsInsideItsBox) {
  const std::string text = "Hx9,{~";
  for (int scale : {1, 3}) {
    EXPECT_EQ(io::text_width(text, scale), static_cast<int>(text.size()) * io::glyph_advance * scale);
    Image img(80 * scale, 20 * scale, 3, 255);
    const int x = 5 * scale + 1, y = 4 * scale + 2;
    io::draw_text(img, x, y, text, red, scale);
    int ink = 0;
    for (int py = 0; py < img.height(); ++py)
      for (int px = 0; px < img.width(); ++px) {
        const bool expected = inked(text, scale, px - x, py - y);
        ASSERT_EQ(at(img, px, py), expected ? red : white) << "scale " << scale << " pixel " << px << ", " << py;
        ink += expected;
      }
    EXPECT_GT(ink, 30 * scale * scale);
    // 'H' fills its first column and '~' its last one: the ink spans the box but the trailing blank column.
    int min_x = img.width(), max_x = -1;
    for (int py = 0; py < img.height(); ++py)
      for (int px = 0; px < img.width(); ++px)
        if (at(img, px, py) == red) {
          min_x = std::min(min_x, px);
          max_x = std::max(max_x, px);
        }
    EXPECT_EQ(min_x, x);
    EXPECT_EQ(max_x, x + io::text_width(text, scale) - scale - 1);
  }
}

TEST(BitmapFont, UpwardTextIsTheUprightTextTurnedCounterClockwise) {
  const std::string text = "Lg7";
  const int scale = 2, w = io::text_width(text, scale), h = io::glyph_height * scale;
  Image upright(w, h, 3, 255), turned(h + 6, w + 9, 3, 255);
  io::draw_text(upright, 0, 0, text, red, scale);
  io::draw_text(turned, 4, 7, text, red, scale, io::TextDirection::up);
  // Box offset (u, v) of the upright text lands at (h - 1 - v, u): the glyph tops face left, read upwards.
  for (int py = 0; py < turned.height(); ++py)
    for (int px = 0; px < turned.width(); ++px) {
      const int u = py - 7, v = h - 1 - (px - 4);
      const bool inside = u >= 0 && u < w && v >= 0 && v < h;
      ASSERT_EQ(at(turned, px, py), inside ? at(upright, u, v) : white) << px << ", " << py;
    }
}

TEST(BitmapFont, ClippingKeepsTheVisiblePart) {
  const std::string text = "Wy@";
  Image whole(100, 60, 3, 255), clipped(20, 12, 3, 255);
  // The text overhangs the small image on the left and at the top.
  io::draw_text(whole, 40 - 7, 20 + 5, text, red, 2);
  io::draw_text(clipped, -7, 5, text, red, 2);
  for (int py = 0; py < clipped.height(); ++py)
    for (int px = 0; px < clipped.width(); ++px) ASSERT_EQ(at(clipped, px, py), at(whole, px + 40, py + 20));
  // Entirely outside: nothing drawn, nothing touched out of bounds.
  io::draw_text(clipped, -100, -100, text, red, 2);
  io::draw_text(clipped, 30, 2, text, red, 2, io::TextDirection::up);
}

TEST(BitmapFont, ControlCharactersDrawAsQuestionMarks) {
  Image a(30, 10, 3, 255), b(30, 10, 3, 255);
  io::draw_text(a, 1, 1, "a\tb", red);
  io::draw_text(b, 1, 1, "a?b", red);
  EXPECT_EQ(a.data(), b.data());
}

TEST(BitmapFont, BadScaleOrImageThrows) {
  Image rgb(20, 10, 3), grey(20, 10, 1);
  EXPECT_THROW(io::draw_text(rgb, 0, 0, "A", red, 0), Error);
  EXPECT_THROW(io::draw_text(grey, 0, 0, "A", red), Error);
  EXPECT_THROW(io::fill_rect(grey, 0, 0, 1, 1, red), Error);
}
