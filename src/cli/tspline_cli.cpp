#include "tspline_cli.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "cli.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/tsm_format.hpp"
#include "trivar/tspline/classification.hpp"
#include "trivar/tspline/t_spline_surface.hpp"

namespace trivar::cli {

bool is_tsm_file(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".tsm";
}

void print_tspline_info(const std::string& path, bool json) {
  const io::TsmModel m = io::read_tsm(path);
  const TSpline& ts = m.spline;
  const TSplineSurface surf(ts);
  const io::TsmReport& r = m.report;
  const PartitionOfUnity& pu = surf.partition_of_unity();
  const TSplineClass cls = classify(ts, surf);
  const std::string as = cls.analysis_suitable ? (*cls.analysis_suitable ? "yes" : "no") : "not classified (even degree)";
  const Box<2> dom = surf.domain();
  nlohmann::json j{{"file", path},
                   {"kind", "T-spline surface"},
                   {"format", "TSM #TS0200"},
                   {"degrees", {ts.degrees[0], ts.degrees[1]}},
                   {"units", r.units},
                   {"domain", {{dom.lo[0], dom.hi[0]}, {dom.lo[1], dom.hi[1]}}},
                   {"t_image", {{"vertices", ts.image.vertices.size()}, {"edges", ts.image.edges.size()},
                                {"links", ts.image.links.size()}, {"faces", ts.image.faces.size()},
                                {"edge_conditions", ts.image.conditions.size()}, {"t_junctions", r.t_junctions}}},
                   {"t_connect", {{"nodes", ts.connect.nodes.size()}, {"repeated_knot_nodes", r.repeated_knot_nodes}}},
                   {"t_pointset", {{"points", ts.pointset.points.size()}}},
                   {"bezier_elements", surf.elements().size()},
                   {"star_points", r.star_points},
                   {"deleted_faces", r.holes},
                   {"deleted_slots", r.deleted},
                   {"partition_of_unity", {{"min_sum", pu.min_sum}, {"max_sum", pu.max_sum},
                                           {"max_defect", pu.max_defect}, {"elements_off", pu.elements_off},
                                           {"sampled_min", pu.sampled_min}, {"sampled_max", pu.sampled_max}}},
                   {"classification", {{"t_junctions", cls.t_junctions}, {"analysis_suitable", as},
                                       {"crossing_extensions", cls.crossing_extensions}, {"standard", cls.standard},
                                       {"semi_standard", cls.semi_standard},
                                       {"linear_independence", to_string(cls.independence)},
                                       {"part42_type", cls.part42_type()}}},
                   {"skipped_records", r.skipped_records}};
  if (json) {
    std::printf("%s\n", j.dump(2).c_str());
    return;
  }
  std::printf("%s: T-spline surface (TSM), degrees %d x %d, units %s\n", path.c_str(), ts.degrees[0], ts.degrees[1],
              r.units.empty() ? "-" : r.units.c_str());
  std::printf("  T-image: %zu vertices, %zu edges, %zu links, %zu faces (%d T-junctions, %d deleted faces, %zu edge conditions)\n",
              ts.image.vertices.size(), ts.image.edges.size(), ts.image.links.size(), ts.image.faces.size(),
              r.t_junctions, r.holes, ts.image.conditions.size());
  std::printf("  T-connect: %zu nodes (%d repeated-knot nodes of Bezier end conditions); T-pointset: %zu points\n",
              ts.connect.nodes.size(), r.repeated_knot_nodes, ts.pointset.points.size());
  std::printf("  domain [%s, %s] x [%s, %s], %zu Bezier elements, star points %d\n", fmt(dom.lo[0]).c_str(),
              fmt(dom.hi[0]).c_str(), fmt(dom.lo[1]).c_str(), fmt(dom.hi[1]).c_str(), surf.elements().size(), r.star_points);
  std::printf("  partition of unity: sum of blending functions from %s to %s (sampled; Bezier bound [%s, %s]), "
              "off 1 on %d element%s (evaluated as sum w P B / sum w B)\n",
              fmt(pu.sampled_min).c_str(), fmt(pu.sampled_max).c_str(), fmt(pu.min_sum).c_str(), fmt(pu.max_sum).c_str(),
              pu.elements_off, pu.elements_off == 1 ? "" : "s");
  std::printf("  classification: analysis-suitable %s (%d crossing T-junction extensions), standard %s, semi-standard %s, "
              "blending functions %s; Part 42 type %s\n",
              as.c_str(), cls.crossing_extensions, cls.standard ? "yes" : "no", cls.semi_standard ? "yes" : "no",
              to_string(cls.independence), cls.part42_type().c_str());
  if (!r.skipped_records.empty()) {
    std::string s;
    for (const auto& [k, n] : r.skipped_records) s += (s.empty() ? "" : ", ") + k + " x" + std::to_string(n);
    std::printf("  records without geometry (skipped): %s\n", s.c_str());
  }
}

void eval_tspline(const std::string& path, const std::vector<double>& params, int order) {
  require(params.size() == 2, "eval: a T-spline surface takes 2 parameters, got " + std::to_string(params.size()));
  require(order <= 1, "eval: T-splines evaluate first derivatives at most (--derivs 0 or 1), got " + std::to_string(order));
  const TSplineSurface surf(io::read_tsm(path).spline);
  const Param<2> u{params[0], params[1]};
  require(surf.locate(u) >= 0, "eval: (" + fmt(u[0]) + ", " + fmt(u[1]) + ") is outside the T-image's faces (domain [" +
                                   fmt(surf.domain().lo[0]) + ", " + fmt(surf.domain().hi[0]) + "] x [" +
                                   fmt(surf.domain().lo[1]) + ", " + fmt(surf.domain().hi[1]) + "])");
  double out[9];
  surf.eval_first_derivatives(u, out);
  std::printf("S   = %s\n", fmt(out, 3).c_str());
  if (order == 1) {
    std::printf("S_u = %s\n", fmt(out + 3, 3).c_str());
    std::printf("S_v = %s\n", fmt(out + 6, 3).c_str());
  }
}

}  // namespace trivar::cli
