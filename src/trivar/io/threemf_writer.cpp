#include "trivar/io/threemf_writer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <vector>

#include "trivar/core/atomic_file.hpp"
#include "trivar/core/error.hpp"
#include "trivar/core/number_format.hpp"
#include "trivar/io/xml_text.hpp"
#include "trivar/io/zip_writer.hpp"
#include "trivar/model/material_fractions.hpp"

namespace trivar::io {

namespace {

constexpr const char* content_types =
    "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    "<Types xmlns=\"http://schemas.openxmlformats.org/package/2006/content-types\">\n"
    " <Default Extension=\"rels\" ContentType=\"application/vnd.openxmlformats-package.relationships+xml\"/>\n"
    " <Default Extension=\"model\" ContentType=\"application/vnd.ms-package.3dmanufacturing-3dmodel+xml\"/>\n"
    "</Types>\n";

constexpr const char* relationships =
    "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    "<Relationships xmlns=\"http://schemas.openxmlformats.org/package/2006/relationships\">\n"
    " <Relationship Target=\"/3D/3dmodel.model\" Id=\"rel0\" "
    "Type=\"http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel\"/>\n"
    "</Relationships>\n";

std::string hex_colour(const Rgba& c) {
  char buf[10];
  if (c.a == 255)
    std::snprintf(buf, sizeof buf, "#%02X%02X%02X", c.r, c.g, c.b);
  else
    std::snprintf(buf, sizeof buf, "#%02X%02X%02X%02X", c.r, c.g, c.b, c.a);
  return buf;
}

}  // namespace

void write_3mf(const std::string& path, const TriangleMesh& mesh, const MaterialTable& materials,
               std::span<const double> vertex_fractions, const std::string& object_name) {
  const std::size_t nv = mesh.vertices.size();
  const auto m = static_cast<std::size_t>(materials.size());
  require(!mesh.triangles.empty(), "write_3mf: the mesh has no triangles (" + path + ")");
  require(m > 0, "write_3mf: no materials (" + path + ")");
  require(vertex_fractions.size() == nv * m, [&] {
    return "write_3mf: " + std::to_string(vertex_fractions.size()) + " fractions for " + std::to_string(nv) +
           " vertices x " + std::to_string(m) + " materials";
  });
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int v : mesh.triangles[t])
      require(v >= 0 && static_cast<std::size_t>(v) < nv,
              [&] { return "write_3mf: triangle " + std::to_string(t) + " names vertex " + std::to_string(v); });

  // One composite per distinct normalised mixture: graded meshes often have large regions of one mixture.
  std::map<std::vector<double>, int> composite_of;
  std::vector<const std::vector<double>*> composites;
  std::vector<int> vertex_composite(nv);
  std::vector<double> mix(m);
  for (std::size_t v = 0; v < nv; ++v) {
    for (double x : mesh.vertices[v])
      require(std::isfinite(x), [&] { return "write_3mf: vertex " + std::to_string(v) + " is not finite"; });
    const std::span<const double> f = vertex_fractions.subspan(v * m, m);
    const double sum = material_fraction_sum(f, [&] { return "write_3mf: vertex " + std::to_string(v); });
    for (std::size_t k = 0; k < m; ++k) mix[k] = f[k] / sum;
    const auto [it, inserted] = composite_of.emplace(mix, static_cast<int>(composites.size()));
    if (inserted) composites.push_back(&it->first);
    vertex_composite[v] = it->second;
  }

  std::ostringstream x;
  x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
       "<model unit=\"millimeter\" xml:lang=\"en-US\" "
       "xmlns=\"http://schemas.microsoft.com/3dmanufacturing/core/2015/02\" "
       "xmlns:m=\"http://schemas.microsoft.com/3dmanufacturing/material/2015/02\" requiredextensions=\"m\">\n"
       " <metadata name=\"Application\">trivar</metadata>\n"
       " <resources>\n"
       "  <basematerials id=\"1\">\n";
  for (const auto& mat : materials.materials())
    x << "   <base name=\"" << xml_escape(mat.name) << "\" displaycolor=\"" << hex_colour(mat.colour) << "\"/>\n";
  x << "  </basematerials>\n  <m:compositematerials id=\"2\" matid=\"1\" matindices=\"";
  for (std::size_t k = 0; k < m; ++k) x << (k ? " " : "") << k;
  x << "\">\n";
  for (const auto* c : composites) {
    x << "   <m:composite values=\"";
    for (std::size_t k = 0; k < m; ++k) {
      if (k) x << ' ';
      write_number(x, (*c)[k]);
    }
    x << "\"/>\n";
  }
  x << "  </m:compositematerials>\n"
       "  <object id=\"3\" type=\"model\" name=\""
    << xml_escape(object_name)
    << "\" pid=\"2\" pindex=\"" << vertex_composite[static_cast<std::size_t>(mesh.triangles[0][0])]
    << "\">\n   <mesh>\n    <vertices>\n";
  for (const auto& p : mesh.vertices) {
    x << "     <vertex x=\"";
    write_number(x, p[0]);
    x << "\" y=\"";
    write_number(x, p[1]);
    x << "\" z=\"";
    write_number(x, p[2]);
    x << "\"/>\n";
  }
  x << "    </vertices>\n    <triangles>\n";
  for (const auto& t : mesh.triangles) {
    const auto c = [&](int i) { return vertex_composite[static_cast<std::size_t>(t[static_cast<std::size_t>(i)])]; };
    x << "     <triangle v1=\"" << t[0] << "\" v2=\"" << t[1] << "\" v3=\"" << t[2] << "\" pid=\"2\" p1=\"" << c(0)
      << "\" p2=\"" << c(1) << "\" p3=\"" << c(2) << "\"/>\n";
  }
  x << "    </triangles>\n   </mesh>\n  </object>\n </resources>\n <build>\n  <item objectid=\"3\"/>\n </build>\n</model>\n";
  const std::string model = std::move(x).str();

  write_file_atomically(
      path,
      [&](std::ostream& os) {
        ZipWriter zip(os);
        zip.add("[Content_Types].xml", content_types);
        zip.add("_rels/.rels", relationships);
        zip.add("3D/3dmodel.model", model);
        zip.finish();
      },
      true);
}

}  // namespace trivar::io
