#pragma once
// Reads a PNG with libpng's low-level reader and no transformations, so tests see exactly the stored pixels,
// palette and transparency.
#include <png.h>

#include <array>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "trivar/model/material_table.hpp"

namespace trivar::test {

struct PngFile {
  png_uint_32 width = 0, height = 0;
  int bit_depth = 0, colour_type = 0;
  std::vector<Rgba> palette;
  bool has_trns = false;
  std::vector<std::vector<png_byte>> rows;  // top row first, as stored

  // Colour at column x of row r (top row 0) of an 8-bit RGB file.
  std::array<std::uint8_t, 3> rgb(int x, int r) const {
    const auto& row = rows.at(static_cast<std::size_t>(r));
    const auto i = static_cast<std::size_t>(3 * x);
    return {row.at(i), row.at(i + 1), row.at(i + 2)};
  }
};

inline PngFile read_png(const std::string& path) {
  PngFile f;
  FILE* fp = std::fopen(path.c_str(), "rb");
  if (!fp) throw std::runtime_error("cannot open " + path);
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    std::fclose(fp);
    throw std::runtime_error("libpng failed reading " + path);
  }
  png_init_io(png, fp);
  png_read_info(png, info);
  png_get_IHDR(png, info, &f.width, &f.height, &f.bit_depth, &f.colour_type, nullptr, nullptr, nullptr);
  png_colorp plte = nullptr;
  int n = 0;
  if (png_get_PLTE(png, info, &plte, &n) & PNG_INFO_PLTE)
    for (int i = 0; i < n; ++i) f.palette.push_back(Rgba{plte[i].red, plte[i].green, plte[i].blue, 255});
  png_bytep trans = nullptr;
  int nt = 0;
  if (png_get_tRNS(png, info, &trans, &nt, nullptr) & PNG_INFO_tRNS) {
    f.has_trns = true;
    for (int i = 0; i < nt; ++i) f.palette.at(static_cast<std::size_t>(i)).a = trans[i];
  }
  const std::size_t row_bytes = png_get_rowbytes(png, info);
  f.rows.assign(f.height, std::vector<png_byte>(row_bytes));
  for (auto& r : f.rows) png_read_row(png, r.data(), nullptr);
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  std::fclose(fp);
  return f;
}

}  // namespace trivar::test
