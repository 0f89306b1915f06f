#include "hier_cli.hpp"

#include <cstdio>

#include "trivar/core/error.hpp"
#include "trivar/io/gismo_xml.hpp"
#include "trivar/io/spline_file.hpp"
#include "trivar/io/step/step_file.hpp"

namespace trivar::cli {

namespace {

bool is_xml(const std::string& path) { return io::file_extension(path) == ".xml"; }

}  // namespace

std::optional<std::vector<AnyHierarchical>> read_hierarchical_if_any(const std::string& path) {
  if (!is_xml(path)) return std::nullopt;
  std::vector<io::GismoGeometry> all = io::read_gismo_xml(path);
  std::size_t hier = 0;
  for (const auto& g : all) hier += g.index() >= 2;
  if (hier == 0) return std::nullopt;
  require(hier == all.size(), path + ": mixes tensor and hierarchical geometries; one command reads one kind");
  std::vector<AnyHierarchical> out;
  for (auto& g : all) {
    if (g.index() == 2) out.emplace_back(std::get<2>(std::move(g)));
    else out.emplace_back(std::get<3>(std::move(g)));
  }
  return out;
}

void print_hierarchical_info(const std::string& file, const std::vector<AnyHierarchical>& objects) {
  std::printf("%s: %zu hierarchical object%s\n", file.c_str(), objects.size(), objects.size() == 1 ? "" : "s");
  for (std::size_t i = 0; i < objects.size(); ++i)
    std::visit(
        [&](const auto& h) {
          constexpr int D = std::is_same_v<std::decay_t<decltype(h)>, HierarchicalSpline<2>> ? 2 : 3;
          const auto& s = h.space();
          std::printf("object %zu: %s %s, %s basis\n", i, D == 2 ? "surface" : "volume",
                      s.basis() == HierarchicalBasis::thb ? "THB spline" : "HB spline", to_string(s.basis()));
          std::printf("  degrees:");
          for (int k = 0; k < D; ++k) std::printf(" %d", s.degree(k));
          std::printf("\n  dimension: %d%s\n  levels: %d\n  functions: %d (", h.dim(), h.is_rational() ? " (rational)" : "",
                      s.num_levels(), s.num_basis());
          for (int l = 0; l < s.num_levels(); ++l) std::printf("%s%d", l ? " + " : "", s.num_basis(l));
          std::printf(" per level)\n  elements: %d\n  domain:", s.num_elements());
          const auto dom = s.domain();
          for (int k = 0; k < D; ++k) std::printf(" [%g, %g]", dom.lo[k], dom.hi[k]);
          std::printf("\n");
        },
        objects[i]);
}

void write_hierarchical_file(const std::string& path, const std::vector<AnyHierarchical>& objects,
                             const std::string& command, const io::LRVtkOptions& vtk) {
  if (io::file_extension(path) == ".vtu") {
    io::write_hierarchical_vtu(path, objects, vtk);
    return;
  }
  if (io::format_of(path) == io::FileFormat::step) {
    io::step::GeometryFileOptions options;
    options.description = "trivar hierarchical splines";
    io::step::write_step(path, {}, {}, objects, options);
    return;
  }
  require(is_xml(path), command + ": hierarchical splines are written to G+Smo .xml, .vtu or STEP files, not '" + path + "'");
  std::vector<io::GismoGeometry> g;
  for (const auto& o : objects) std::visit([&](const auto& h) { g.emplace_back(h); }, o);
  io::write_gismo_xml(path, g);
}

}  // namespace trivar::cli
