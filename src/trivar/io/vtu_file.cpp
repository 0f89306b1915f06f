#include "trivar/io/vtu_file.hpp"

#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <ostream>

#include "trivar/core/atomic_file.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/xml_text.hpp"

namespace trivar::io {

namespace {

static_assert(std::endian::native == std::endian::little, "the .vtu files declare byte_order=\"LittleEndian\"");

// VTK's own default block size: a reader decompresses one block at a time, so blocks bound its buffers.
constexpr std::size_t kBlockSize = std::size_t{1} << 15;

void put_u64(std::string& s, std::size_t at, std::uint64_t v) { std::memcpy(s.data() + at, &v, sizeof v); }

void write_array_element(std::ostream& os, const VtuDataArray& a, std::uint64_t offset) {
  os << "        <DataArray type=\"" << a.type << "\"";
  if (!a.name.empty()) os << " Name=\"" << xml_escape(a.name) << "\"";
  os << " NumberOfComponents=\"" << a.components << "\" format=\"appended\" offset=\"" << offset << "\"/>\n";
}

}  // namespace

std::string VtuDataArray::compress(const void* data, std::size_t bytes) {
  const std::size_t blocks = (bytes + kBlockSize - 1) / kBlockSize;
  const auto* in = static_cast<const Bytef*>(data);
  // Blocks are compressed independently (in parallel), then packed behind the header. Level 1: about twice
  // as fast as zlib's default for 14 % more bytes on a cubic solution field.
  std::vector<std::string> out(blocks);
  bool ok = true;
#pragma omp parallel for schedule(dynamic) if (blocks > 8)
  for (std::size_t b = 0; b < blocks; ++b) {
    const std::size_t size = std::min(kBlockSize, bytes - b * kBlockSize);
    uLongf packed = compressBound(static_cast<uLong>(size));
    out[b].resize(packed);
    if (compress2(reinterpret_cast<Bytef*>(out[b].data()), &packed, in + b * kBlockSize, static_cast<uLong>(size),
                  Z_BEST_SPEED) != Z_OK) {
#pragma omp atomic write
      ok = false;
    }
    out[b].resize(packed);
  }
  require(ok, "vtu: zlib compression failed");
  std::string encoded((3 + blocks) * sizeof(std::uint64_t), '\0');
  put_u64(encoded, 0, blocks);
  put_u64(encoded, 8, kBlockSize);
  put_u64(encoded, 16, bytes % kBlockSize);
  for (std::size_t b = 0; b < blocks; ++b) put_u64(encoded, (3 + b) * 8, out[b].size());
  for (const std::string& s : out) encoded += s;
  return encoded;
}

void write_vtu_file(const std::string& path, const std::vector<VtuPiece>& pieces) {
  write_file_atomically(
      path,
      [&](std::ostream& os) {
        os << "<?xml version=\"1.0\"?>\n"
              "<VTKFile type=\"UnstructuredGrid\" version=\"2.1\" byte_order=\"LittleEndian\" "
              "header_type=\"UInt64\" compressor=\"vtkZLibDataCompressor\">\n"
              "  <UnstructuredGrid>\n";
        std::uint64_t offset = 0;
        std::vector<const VtuDataArray*> order;
        auto element = [&](const VtuDataArray& a) {
          write_array_element(os, a, offset);
          offset += a.encoded.size();
          order.push_back(&a);
        };
        for (const VtuPiece& p : pieces) {
          os << "    <Piece NumberOfPoints=\"" << p.num_points << "\" NumberOfCells=\"" << p.num_cells << "\">\n";
          os << "      <PointData" << p.point_data_attributes << ">\n";
          for (const auto& a : p.point_data) element(a);
          os << "      </PointData>\n      <CellData" << p.cell_data_attributes << ">\n";
          for (const auto& a : p.cell_data) element(a);
          os << "      </CellData>\n      <Points>\n";
          element(p.points);
          os << "      </Points>\n      <Cells>\n";
          element(p.connectivity);
          element(p.offsets);
          element(p.types);
          os << "      </Cells>\n    </Piece>\n";
        }
        os << "  </UnstructuredGrid>\n  <AppendedData encoding=\"raw\">\n   _";
        for (const VtuDataArray* a : order) os.write(a->encoded.data(), static_cast<std::streamsize>(a->encoded.size()));
        os << "\n  </AppendedData>\n</VTKFile>\n";
      },
      true);
}

}  // namespace trivar::io
