#include "trivar/io/stl_writer.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <ostream>

#include "trivar/core/atomic_file.hpp"
#include "trivar/core/error.hpp"

namespace trivar::io {

namespace {

static_assert(std::endian::native == std::endian::little, "binary STL is little-endian; add byte swapping");

void put(std::ostream& os, float x) { os.write(reinterpret_cast<const char*>(&x), sizeof x); }

}  // namespace

void write_stl(const std::string& path, const TriangleMesh& mesh, const std::string& header) {
  require(mesh.triangles.size() <= std::numeric_limits<std::uint32_t>::max(),
          [&] { return "write_stl: " + std::to_string(mesh.triangles.size()) + " triangles exceed the STL count"; });
  const auto n = static_cast<int>(mesh.vertices.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int v : mesh.triangles[t])
      require(v >= 0 && v < n, [&] { return "write_stl: triangle " + std::to_string(t) + " names vertex " + std::to_string(v); });
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
    for (double x : mesh.vertices[v])
      require(std::isfinite(x), [&] { return "write_stl: vertex " + std::to_string(v) + " is not finite"; });

  write_file_atomically(
      path,
      [&](std::ostream& os) {
        char head[80] = {};
        // A header starting with "solid" makes some readers take the file for ASCII STL.
        const std::string text = header.rfind("solid", 0) == 0 ? "trivar " + header : header;
        std::memcpy(head, text.data(), std::min<std::size_t>(text.size(), sizeof head));
        os.write(head, sizeof head);
        const auto count = static_cast<std::uint32_t>(mesh.triangles.size());
        os.write(reinterpret_cast<const char*>(&count), sizeof count);
        for (const auto& t : mesh.triangles) {
          const auto& a = mesh.vertices[t[0]];
          const auto& b = mesh.vertices[t[1]];
          const auto& c = mesh.vertices[t[2]];
          const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
          double nrm[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
          const double len = std::sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
          for (double& x : nrm) x = len > 0 ? x / len : 0.0;
          for (double x : nrm) put(os, static_cast<float>(x));
          for (int v : t)
            for (double x : mesh.vertices[v]) put(os, static_cast<float>(x));
          const std::uint16_t attribute = 0;
          os.write(reinterpret_cast<const char*>(&attribute), sizeof attribute);
        }
      },
      true);
}

}  // namespace trivar::io
