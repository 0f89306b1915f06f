#include "trivar/io/amf_writer.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "trivar/core/atomic_file.hpp"
#include "trivar/core/error.hpp"
#include "trivar/core/number_format.hpp"
#include "trivar/io/xml_text.hpp"
#include "trivar/io/zip_writer.hpp"
#include "trivar/model/material_fractions.hpp"

namespace trivar::io {

namespace {

void write_colour(std::ostream& os, double r, double g, double b, double a) {
  const char* tags[] = {"r", "g", "b", "a"};
  const double v[] = {r, g, b, a};
  os << "<color>";
  for (int i = 0; i < 4; ++i) {
    os << '<' << tags[i] << '>';
    write_number(os, v[i]);
    os << "</" << tags[i] << '>';
  }
  os << "</color>";
}

}  // namespace

void write_amf(const std::string& path, const TriangleMesh& mesh, const MaterialTable& materials,
               const AmfGrading& grading, std::span<const double> vertex_fractions, const AmfOptions& options) {
  const std::size_t nv = mesh.vertices.size();
  const int m = materials.size();
  const auto mu = static_cast<std::size_t>(m);
  require(!mesh.triangles.empty(), "write_amf: the mesh has no triangles (" + path + ")");
  require(m > 0, "write_amf: no materials (" + path + ")");
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int v : mesh.triangles[t])
      require(v >= 0 && static_cast<std::size_t>(v) < nv,
              [&] { return "write_amf: triangle " + std::to_string(t) + " names vertex " + std::to_string(v); });
  for (std::size_t v = 0; v < nv; ++v)
    for (double x : mesh.vertices[v])
      require(std::isfinite(x), [&] { return "write_amf: vertex " + std::to_string(v) + " is not finite"; });
  const bool graded = !grading.formulas.empty();
  if (graded) {
    require(grading.formulas.size() == mu, "write_amf: " + std::to_string(grading.formulas.size()) +
                                               " composite formulas for " + std::to_string(m) + " materials");
    for (std::size_t k = 0; k < mu; ++k)
      require(grading.formulas[k].find_first_not_of(" \t\r\n") != std::string::npos,
              "write_amf: composite formula of material '" + materials[static_cast<int>(k)].name + "' is empty");
  } else {
    require(grading.base_material >= 0 && grading.base_material < m,
            "write_amf: base material " + std::to_string(grading.base_material) + " of " + std::to_string(m));
  }
  require(vertex_fractions.empty() || vertex_fractions.size() == nv * mu, [&] {
    return "write_amf: " + std::to_string(vertex_fractions.size()) + " fractions for " + std::to_string(nv) +
           " vertices x " + std::to_string(m) + " materials";
  });

  std::ostringstream x;
  x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<amf unit=\"millimeter\" version=\"1.1\">\n"
       " <metadata type=\"producer\">trivar</metadata>\n";
  for (int k = 0; k < m; ++k) {
    const auto& c = materials[k].colour;
    x << " <material id=\"" << k + 1 << "\"><metadata type=\"name\">" << xml_escape(materials[k].name) << "</metadata>";
    write_colour(x, c.r / 255.0, c.g / 255.0, c.b / 255.0, c.a / 255.0);
    x << "</material>\n";
  }
  if (graded) {
    x << " <material id=\"" << m + 1 << "\"><metadata type=\"name\">graded</metadata>\n";
    for (int k = 0; k < m; ++k)
      x << "  <composite materialid=\"" << k + 1 << "\">" << xml_escape(grading.formulas[static_cast<std::size_t>(k)])
        << "</composite>\n";
    x << " </material>\n";
  }
  x << " <object id=\"" << m + 2 << "\"><mesh>\n  <vertices>\n";
  for (std::size_t v = 0; v < nv; ++v) {
    const auto& p = mesh.vertices[v];
    x << "   <vertex><coordinates><x>";
    write_number(x, p[0]);
    x << "</x><y>";
    write_number(x, p[1]);
    x << "</y><z>";
    write_number(x, p[2]);
    x << "</z></coordinates>";
    if (!vertex_fractions.empty()) {
      const std::span<const double> f = vertex_fractions.subspan(v * mu, mu);
      const double sum = material_fraction_sum(f, [&] { return "write_amf: vertex " + std::to_string(v); });
      double rgba[4] = {0, 0, 0, 0};
      for (std::size_t k = 0; k < mu; ++k) {
        const auto& c = materials[static_cast<int>(k)].colour;
        rgba[0] += f[k] * c.r, rgba[1] += f[k] * c.g, rgba[2] += f[k] * c.b, rgba[3] += f[k] * c.a;
      }
      const double s = 1.0 / (255.0 * sum);
      write_colour(x, rgba[0] * s, rgba[1] * s, rgba[2] * s, rgba[3] * s);
    }
    x << "</vertex>\n";
  }
  x << "  </vertices>\n  <volume materialid=\"" << (graded ? m + 1 : grading.base_material + 1) << "\">\n";
  for (const auto& t : mesh.triangles)
    x << "   <triangle><v1>" << t[0] << "</v1><v2>" << t[1] << "</v2><v3>" << t[2] << "</v3></triangle>\n";
  x << "  </volume>\n </mesh></object>\n</amf>\n";
  const std::string text = std::move(x).str();

  write_file_atomically(
      path,
      [&](std::ostream& os) {
        if (!options.zip) {
          os.write(text.data(), static_cast<std::streamsize>(text.size()));
          return;
        }
        ZipWriter zip(os);
        zip.add(std::filesystem::path(path).filename().string(), text);
        zip.finish();
      },
      true);
}

}  // namespace trivar::io
