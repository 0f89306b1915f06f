#include "trivar/io/png_writer.hpp"

#include <png.h>
#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <ostream>

#include "trivar/core/atomic_file.hpp"
#include "trivar/core/error.hpp"

namespace trivar::io {

namespace {

struct PngLayout {
  int width = 0, height = 0, bit_depth = 8, colour_type = PNG_COLOR_TYPE_GRAY;
  std::size_t row_bytes = 0;
};

// libpng reports errors by longjmp; the handler jumps without printing and encode() turns it into an Error.
[[noreturn]] void on_error(png_structp png, png_const_charp) { png_longjmp(png, 1); }
void on_warning(png_structp, png_const_charp) {}

void on_write(png_structp png, png_bytep data, png_size_t n) {
  auto* os = static_cast<std::ostream*>(png_get_io_ptr(png));
  os->write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(n));
  if (!*os) png_error(png, "write failed");
}
void on_flush(png_structp png) { static_cast<std::ostream*>(png_get_io_ptr(png))->flush(); }

// Rows are stored top-down in `pixels` (row r of the PNG at r * row_bytes). A libpng error jumps back into
// this frame across libpng's C frames only, so no destructor is skipped.
void encode(std::ostream& os, const PngLayout& layout, std::vector<png_byte>& pixels,
            const std::vector<Rgba>* palette, int level, const std::string& path) {
  std::vector<png_bytep> rows(static_cast<std::size_t>(layout.height));
  for (std::size_t r = 0; r < rows.size(); ++r) rows[r] = pixels.data() + r * layout.row_bytes;
  std::vector<png_color> colours;
  std::vector<png_byte> alpha;
  if (palette) {
    for (const auto& c : *palette) {
      colours.push_back(png_color{c.r, c.g, c.b});
      alpha.push_back(c.a);
    }
    // tRNS may stop after the last translucent entry; without one the chunk is omitted.
    while (!alpha.empty() && alpha.back() == 255) alpha.pop_back();
  }

  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, on_error, on_warning);
  require(png != nullptr, "write_png: libpng initialisation failed for " + path);
  png_infop info = png_create_info_struct(png);
  if (info == nullptr || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw Error("write_png: libpng failed writing " + path);
  }
  png_set_write_fn(png, &os, on_write, on_flush);
  png_set_compression_level(png, level);
  png_set_IHDR(png, info, static_cast<png_uint_32>(layout.width), static_cast<png_uint_32>(layout.height),
               layout.bit_depth, layout.colour_type, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  if (palette) {
    png_set_PLTE(png, info, colours.data(), static_cast<int>(colours.size()));
    if (!alpha.empty()) png_set_tRNS(png, info, alpha.data(), static_cast<int>(alpha.size()), nullptr);
    // Filters rarely help indexed images of large flat regions and cost time.
    png_set_filter(png, 0, PNG_FILTER_NONE);
  }
  png_write_info(png, info);
  png_write_image(png, rows.data());
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
}

void require_level(int level, const std::string& path) {
  require(level >= 0 && level <= 9, "write_png: compression level " + std::to_string(level) + " is not 0..9 (" + path + ")");
}

void require_size(int width, int height, const std::string& path) {
  require(width > 0 && height > 0, "write_png: image " + std::to_string(width) + " x " + std::to_string(height) +
                                       " has no pixels (" + path + ")");
  require(width <= 0x7fffffff / 4 && height <= 1000000,
          "write_png: image " + std::to_string(width) + " x " + std::to_string(height) + " is too large (" + path + ")");
}

}  // namespace

std::vector<Rgba> material_palette(const MaterialTable& materials, Rgba background) {
  std::vector<Rgba> palette{background};
  for (const auto& m : materials.materials()) palette.push_back(m.colour);
  return palette;
}

void write_palette_png(const std::string& path, const LabelImage& labels, const std::vector<Rgba>& palette,
                       int compression_level) {
  require_size(labels.width(), labels.height(), path);
  require_level(compression_level, path);
  require(labels.channels() == 1, "write_palette_png: label image has " + std::to_string(labels.channels()) + " channels");
  require(!palette.empty() && palette.size() <= 256,
          "write_palette_png: palette of " + std::to_string(palette.size()) + " colours (1..256 allowed) for " + path);
  PngLayout layout{labels.width(), labels.height(), 8, PNG_COLOR_TYPE_PALETTE,
                   static_cast<std::size_t>(labels.width())};
  std::vector<png_byte> pixels(layout.row_bytes * static_cast<std::size_t>(layout.height));
  for (int r = 0; r < layout.height; ++r) {
    const int y = layout.height - 1 - r;
    for (int x = 0; x < layout.width; ++x) {
      const std::uint8_t l = labels(x, y);
      require(l < palette.size(), [&] {
        return "write_palette_png: label " + std::to_string(l) + " at pixel (" + std::to_string(x) + ", " +
               std::to_string(y) + ") is beyond the palette of " + std::to_string(palette.size()) + " colours";
      });
      pixels[static_cast<std::size_t>(r) * layout.row_bytes + static_cast<std::size_t>(x)] = l;
    }
  }
  write_file_atomically(path, [&](std::ostream& os) { encode(os, layout, pixels, &palette, compression_level, path); }, true);
}

void write_bitmap_png(const std::string& path, const LabelImage& labels, int label, int compression_level) {
  require_size(labels.width(), labels.height(), path);
  require_level(compression_level, path);
  require(labels.channels() == 1, "write_bitmap_png: label image has " + std::to_string(labels.channels()) + " channels");
  require(label >= 0 && label <= 255, "write_bitmap_png: label " + std::to_string(label) + " is not a byte");
  PngLayout layout{labels.width(), labels.height(), 1, PNG_COLOR_TYPE_GRAY,
                   (static_cast<std::size_t>(labels.width()) + 7) / 8};
  std::vector<png_byte> pixels(layout.row_bytes * static_cast<std::size_t>(layout.height), 0);
  for (int r = 0; r < layout.height; ++r) {
    const int y = layout.height - 1 - r;
    png_byte* row = pixels.data() + static_cast<std::size_t>(r) * layout.row_bytes;
    // PNG packs sub-byte pixels most significant bit first.
    for (int x = 0; x < layout.width; ++x)
      if (labels(x, y) == label) row[x / 8] = static_cast<png_byte>(row[x / 8] | (0x80 >> (x % 8)));
  }
  write_file_atomically(path, [&](std::ostream& os) { encode(os, layout, pixels, nullptr, compression_level, path); }, true);
}

void write_png(const std::string& path, const LayerImage<std::uint8_t>& image) {
  require_size(image.width(), image.height(), path);
  static constexpr int types[] = {PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                                  PNG_COLOR_TYPE_RGB_ALPHA};
  const int c = image.channels();
  require(c >= 1 && c <= 4, "write_png: " + std::to_string(c) + " channels (1 to 4 allowed) for " + path);
  PngLayout layout{image.width(), image.height(), 8, types[c - 1],
                   static_cast<std::size_t>(image.width()) * static_cast<std::size_t>(c)};
  std::vector<png_byte> pixels(layout.row_bytes * static_cast<std::size_t>(layout.height));
  for (int r = 0; r < layout.height; ++r) {
    const std::uint8_t* src = image.pixel(0, layout.height - 1 - r);
    std::copy(src, src + layout.row_bytes, pixels.data() + static_cast<std::size_t>(r) * layout.row_bytes);
  }
  write_file_atomically(path, [&](std::ostream& os) { encode(os, layout, pixels, nullptr, Z_DEFAULT_COMPRESSION, path); }, true);
}

}  // namespace trivar::io
