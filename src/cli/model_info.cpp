// Description of a V-model for `trivar info`: topology counts, boundary, volume, bounds and attributes.
#include <algorithm>
#include <cstdio>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "cli.hpp"
#include "trivar/model/material_fractions.hpp"
#include "trivar/model/model_boundary.hpp"
#include "trivar/model/trimmed_interfaces.hpp"
#include "trivar/model/trimmed_tessellation.hpp"
#include "trivar/spline/jacobian.hpp"

namespace trivar::cli {

namespace {

const char* kind_word(Attribute::Kind k) {
  switch (k) {
    case Attribute::Kind::constant: return "constant";
    case Attribute::Kind::field: return "field";
    case Attribute::Kind::expression: return "expression";
  }
  return "?";
}

nlohmann::json describe(const VModel& m) {
  check_material_fractions(m);
  const VTopology& t = m.topology();
  // A trimmed cell's boundary is its trimming surfaces, closed by construction.
  const bool closed = has_trimmed_cells(m) || model_boundary(m).closed();
  const Box<3> box = m.bounding_box();
  nlohmann::json j{{"kind", "vmodel"},
                   {"cells", m.num_cells()},
                   {"shared_surfaces", t.num_shared_surfaces()},
                   {"boundary_surfaces", t.num_boundary_surfaces()},
                   {"curves", t.curves.size()},
                   {"points", t.points.size()},
                   {"non_conforming_faces", t.non_conforming.size()},
                   {"boundary_closed", closed},
                   {"trimmed_cells", std::count_if(m.cells().begin(), m.cells().end(), [](const VCell& c) { return c.is_trimmed(); })},
                   {"gluing_tolerance", t.tolerance},
                   {"volume", m.volume()},
                   {"control_bounds", {{"lo", box.lo}, {"hi", box.hi}}}};
  std::map<std::string, nlohmann::json> attrs;
  for (int i = 0; i < m.num_cells(); ++i)
    for (const auto& [name, a] : m.cell(i).attributes()) {
      nlohmann::json& e = attrs[name];
      e["components"] = a.components();
      e["cells"].push_back(i);
      e["kinds"][kind_word(a.kind())] = true;
    }
  j["attributes"] = nlohmann::json::object();
  for (auto& [name, e] : attrs) {
    nlohmann::json kinds = nlohmann::json::array();
    for (const auto& [k, v] : e["kinds"].items()) kinds.push_back(k);
    e["kinds"] = kinds;
    j["attributes"][name] = e;
  }
  for (const NonConformingFace& f : t.non_conforming) j["non_conforming"].push_back(f.describe());
  if (std::all_of(m.cells().begin(), m.cells().end(), [](const VCell& c) { return c.is_trimmed(); })) {
    // The V-topology across the trimming faces: shared faces, boundary faces, neighbours, and the boundary mesh
    // of the whole model (the shared faces left out).
    const TrimmedInterfaces ti = trimmed_interfaces(m);
    const ModelTessellation b = trimmed_boundary_mesh(m);
    nlohmann::json nc = nlohmann::json::array();
    for (const TrimmedFaceRef& f : ti.non_conforming) nc.push_back({{"cell", f.cell}, {"face", f.face}});
    j["trimmed_topology"] = {{"shared_faces", ti.shared},
                             {"boundary_faces", ti.boundary},
                             {"non_conforming_faces", nc},
                             {"neighbours", ti.neighbours},
                             {"curves", ti.curves.size()},
                             {"points", ti.points.size()},
                             {"euler_characteristic", ti.boundary_euler},
                             {"cell_euler_characteristics", ti.cell_euler},
                             {"defects", ti.defects},
                             {"boundary_mesh", {{"triangles", b.mesh.triangles.size()},
                                                {"watertight", is_watertight(b.mesh)},
                                                {"euler_characteristic", euler_characteristic(b.mesh)}}}};
    // The trimmed cells' boxes are no part of the model: the topology is that of their trimming faces.
    j["shared_surfaces"] = ti.shared;
    j["boundary_surfaces"] = ti.boundary;
    j["curves"] = ti.curves.size();
    j["points"] = ti.points.size();
    j["non_conforming_faces"] = ti.non_conforming.size();
  }
  for (int i = 0; i < m.num_cells(); ++i) {
    const TensorSpline<3>& g = m.cell(i).geometry();
    const JacobianReport<3> r = check_jacobian(g);
    j["cell_info"].push_back({{"degrees", {g.degree(0), g.degree(1), g.degree(2)}},
                              {"counts", {g.count(0), g.count(1), g.count(2)}},
                              {"rational", g.is_rational()},
                              {"jacobian", r.valid ? "valid" : r.invalid ? "invalid" : "undecided"},
                              {"min_det_j_lower_bound", r.min_lower_bound}});
    if (const TrimmedSolid* trim = m.cell(i).trim()) {
      std::map<std::string, int> kinds;
      for (const TrimmedFace& f : trim->boundary().faces) ++kinds[f.kind.empty() ? "unknown" : f.kind];
      j["cell_info"].back()["trim"] = {{"faces", trim->boundary().faces.size()},
                                       {"faces_by_kind", kinds},
                                       {"triangles", trim->boundary().mesh.triangles.size()},
                                       {"chordal_tolerance", trim->boundary().chordal_tolerance},
                                       {"volume", trim->volume()}};
    }
  }
  return j;
}

}  // namespace

void print_model_info(const std::string& path, const VModel& m, bool json) {
  const nlohmann::json d = describe(m);
  if (json) {
    nlohmann::json out{{"file", path}};
    out.update(d);
    std::printf("%s\n", out.dump(2).c_str());
    return;
  }
  std::printf("%s: V-model, %d cell%s\n", path.c_str(), m.num_cells(), m.num_cells() == 1 ? "" : "s");
  std::printf("  topology: %d shared surfaces, %d boundary surfaces, %zu curves, %zu points\n",
              d["shared_surfaces"].get<int>(), d["boundary_surfaces"].get<int>(), d["curves"].get<std::size_t>(),
              d["points"].get<std::size_t>());
  std::printf("  boundary: %s\n", d["boundary_closed"].get<bool>() ? "closed" : "open");
  std::printf("  non-conforming faces: %zu\n", d["non_conforming_faces"].get<std::size_t>());
  for (const auto& s : d.value("non_conforming", nlohmann::json::array())) std::printf("    %s\n", s.get<std::string>().c_str());
  if (d.contains("trimmed_topology")) {
    const nlohmann::json& t = d["trimmed_topology"];
    const nlohmann::json& b = t["boundary_mesh"];
    std::printf("  trimming faces: %d shared by two cells, %d on the boundary, %zu non-conforming; boundary mesh %zu "
                "triangles, %s, Euler characteristic %d\n",
                t["shared_faces"].get<int>(), t["boundary_faces"].get<int>(), t["non_conforming_faces"].size(),
                b["triangles"].get<std::size_t>(), b["watertight"].get<bool>() ? "watertight" : "NOT watertight",
                b["euler_characteristic"].get<int>());
    std::printf("  trimming edges and vertices: %zu V-curves, %zu V-points; boundary V - E + F = %d\n",
                t["curves"].get<std::size_t>(), t["points"].get<std::size_t>(), t["euler_characteristic"].get<int>());
    for (const auto& line : t["defects"]) std::printf("    defect: %s\n", line.get<std::string>().c_str());
  }
  std::printf("  volume: %s\n", fmt(d["volume"].get<double>()).c_str());
  const Box<3> box = m.bounding_box();
  std::printf("  control bounding box: [%s, %s] x [%s, %s] x [%s, %s]\n", fmt(box.lo[0]).c_str(), fmt(box.hi[0]).c_str(),
              fmt(box.lo[1]).c_str(), fmt(box.hi[1]).c_str(), fmt(box.lo[2]).c_str(), fmt(box.hi[2]).c_str());
  for (const auto& [name, e] : d["attributes"].items())
    std::printf("  attribute %s: %d component%s, %s, on %zu of %d cells\n", name.c_str(), e["components"].get<int>(),
                e["components"].get<int>() == 1 ? "" : "s", e["kinds"].dump().c_str(), e["cells"].size(), m.num_cells());
  for (int i = 0; i < m.num_cells(); ++i) {
    const nlohmann::json& c = d["cell_info"][static_cast<std::size_t>(i)];
    std::printf("  cell %d: degrees %s, control points %s, %s, Jacobian %s, min det J >= %s\n", i,
                c["degrees"].dump().c_str(), c["counts"].dump().c_str(), c["rational"].get<bool>() ? "rational" : "polynomial",
                c["jacobian"].get<std::string>().c_str(), fmt(c["min_det_j_lower_bound"].get<double>()).c_str());
    if (!c.contains("trim")) continue;
    if (d.contains("trimmed_topology") && m.num_cells() > 1)
      std::printf("    neighbours across shared faces: %s; boundary Euler characteristic %d\n",
                  d["trimmed_topology"]["neighbours"][static_cast<std::size_t>(i)].dump().c_str(),
                  d["trimmed_topology"]["cell_euler_characteristics"][static_cast<std::size_t>(i)].get<int>());
    const nlohmann::json& t = c["trim"];
    std::string kinds;
    for (const auto& [k, n] : t["faces_by_kind"].items()) kinds += (kinds.empty() ? "" : ", ") + std::to_string(n.get<int>()) + " " + k;
    std::printf("    trimmed by %zu faces (%s), volume %s (exact boundary), boundary mesh %zu triangles within %s\n",
                t["faces"].get<std::size_t>(), kinds.c_str(), fmt(t["volume"].get<double>()).c_str(),
                t["triangles"].get<std::size_t>(), fmt(t["chordal_tolerance"].get<double>()).c_str());
  }
}

}  // namespace trivar::cli
