#pragma once
// A fixed 5 x 7 pixel bitmap font for printable ASCII (32..126), drawn at an integer scale into RGB images: the
// labels of generated figures (tick values, axis names, legends). It is hand-written because a font library
// such as FreeType would bring a library and a font file to locate at run time for a few short labels.
#include <array>
#include <cstdint>
#include <string_view>

#include "trivar/io/fill_rect.hpp"

namespace trivar::io {

// Ink of a glyph; the advance leaves one blank column between characters.
inline constexpr int glyph_width = 5, glyph_height = 7, glyph_advance = 6;

// Rows of the glyph of `c`, top row first, bit 4 = leftmost column; characters outside 32..126 draw as '?'.
const std::array<std::uint8_t, glyph_height>& glyph(char c);

// Extent of `text` along its direction, text.size() * glyph_advance * scale: the trailing blank column is
// included so that the widths of strings drawn one after the other add up.
int text_width(std::string_view text, int scale = 1);

// right: left to right; up: rotated a quarter turn counter-clockwise, read bottom to top (a y-axis label).
enum class TextDirection { right, up };

// Draws `text` in the box whose lower-left corner is (x, y) (the image's y axis points up, see layer_image.hpp):
// text_width wide and glyph_height * scale high, or the transpose for `up`. Ink outside the image is dropped.
// Throws trivar::Error for a scale below 1; the image must be RGB (see fill_rect).
void draw_text(LayerImage<std::uint8_t>& image, int x, int y, std::string_view text, const Rgb& colour,
               int scale = 1, TextDirection direction = TextDirection::right);

}  // namespace trivar::io
