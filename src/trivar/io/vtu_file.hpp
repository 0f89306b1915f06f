#pragma once
// VTK XML UnstructuredGrid file (.vtu) in binary: every DataArray in the appended section, raw (no base64),
// compressed with zlib (compressor="vtkZLibDataCompressor", header_type="UInt64"). Each array is stored as
//   [number of blocks][uncompressed block size][uncompressed size of the last block, 0 when full]
//   [compressed size of block 0] ... [compressed size of block n-1]  (all UInt64)
// followed by the compressed blocks, and its DataArray element gives the offset of that header from the
// first byte after the '_' that opens the appended data. File version 2.1: VTK >= 9 point order of
// higher-order hexahedra.
#include <cstdint>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

namespace trivar::io {

// One DataArray, compressed as soon as it is made so the caller can free the values.
struct VtuDataArray {
  std::string name;  // empty for the point coordinates
  const char* type = "Float64";
  int components = 1;
  std::string encoded;  // block header and compressed blocks

  template <class T>
  static VtuDataArray make(std::string name, int components, std::span<const T> values) {
    static_assert(std::is_same_v<T, double> || std::is_same_v<T, std::int64_t> || std::is_same_v<T, std::int32_t> ||
                  std::is_same_v<T, std::uint8_t>);
    const char* type = std::is_same_v<T, double>         ? "Float64"
                       : std::is_same_v<T, std::int64_t> ? "Int64"
                       : std::is_same_v<T, std::int32_t> ? "Int32"
                                                         : "UInt8";
    return {std::move(name), type, components, compress(values.data(), values.size_bytes())};
  }
  template <class T>
  static VtuDataArray make(std::string name, int components, const std::vector<T>& values) {
    return make(std::move(name), components, std::span<const T>(values));
  }

 private:
  static std::string compress(const void* data, std::size_t bytes);
};

struct VtuPiece {
  std::int64_t num_points = 0, num_cells = 0;
  std::vector<VtuDataArray> point_data, cell_data;
  // Attributes of <PointData> / <CellData> naming special arrays, e.g. RationalWeights="RationalWeights".
  std::string point_data_attributes, cell_data_attributes;
  VtuDataArray points;  // Float64, 3 components
  VtuDataArray connectivity, offsets, types;  // Int64, Int64, UInt8
};

// Writes the pieces atomically (core/atomic_file.hpp). Throws trivar::Error when the file cannot be written.
void write_vtu_file(const std::string& path, const std::vector<VtuPiece>& pieces);

}  // namespace trivar::io
