// trivar boolean A B --op union|difference|intersection -o C.json: the Boolean of two V-models (the cad
// layer), attributes blended where the operands overlap; trivar boolean A --split plane:...|surface.g2 -o C.json
// splits A's cells along a plane or a B-spline surface.
#include <cmath>
#include <cstdio>
#include <string>

#include "cli.hpp"
#include "trivar/cad/boolean.hpp"
#include "trivar/cad/split.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/spline_file.hpp"
#include "trivar/io/vmodel_json.hpp"
#include "trivar/model/trimmed_tessellation.hpp"

namespace trivar::cli {

void add_boolean_command(CLI::App& app, Context&) {
  auto* cmd = app.add_subcommand("boolean", "Union, difference or intersection of two V-models (a V-model of trimmed "
                                            "cells, attributes blended where the operands overlap), or a split of one "
                                            "by a plane or a B-spline surface");
  struct Args {
    std::string a, b, out, op, split, rule = "a", weight;
    std::vector<std::string> per_attribute;
    double tolerance = 0, fuzzy = 1e-9;
    int field_degree = 3, field_elements = 6;
    bool json = false;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("A", a->a, "First operand: a V-model (.json) or a spline file of volumes")->required();
  cmd->add_option("B", a->b, "Second operand (not with --split)");
  cmd->add_option("--op", a->op, "union, difference (A minus B) or intersection")
      ->check(CLI::IsMember({"union", "difference", "intersection"}));
  cmd->add_option("--split", a->split,
                  "Split A instead: plane:px,py,pz,nx,ny,nz, or a spline file (.g2, .json, ...) holding one B-spline "
                  "surface that reaches across A; every cell it crosses becomes two trimmed cells");
  cmd->add_option("-o,--output", a->out, "Output V-model (.json)")->required();
  cmd->add_option("--rule", a->rule,
                  "Attributes where A and B overlap: a, b, average, formula ((1-w) A + w B, w from --weight) or "
                  "distance (weights by the distances to the operands' boundaries)")
      ->check(CLI::IsMember({"a", "b", "average", "formula", "distance"}))
      ->capture_default_str();
  cmd->add_option("--attribute-rule", a->per_attribute, "NAME=RULE: the rule of one attribute (repeatable)");
  cmd->add_option("--weight", a->weight, "Weight w of B in x, y, z for the formula rule, e.g. \"min(1, max(0, x/10))\"");
  cmd->add_option("--tolerance", a->tolerance,
                  "Chordal tolerance of the result cells' meshes, model units (default: 1e-3 of the operands' diagonal)")
      ->check(at_least(0));
  cmd->add_option("--fuzzy", a->fuzzy, "Distance under which faces count as coincident, relative to the operands' diagonal")
      ->check(at_least(0))
      ->capture_default_str();
  cmd->add_option("--field-degree", a->field_degree, "Degree of fitted attribute fields (distance blends, fields)")
      ->check(CLI::Range(1, 7))
      ->capture_default_str();
  cmd->add_option("--field-elements", a->field_elements, "Elements per direction of fitted attribute fields")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  cmd->add_flag("--json", a->json, "Print the report as one JSON document");
  cmd->callback([a] {
    cad::BooleanOptions o;
    o.default_rule = {cad::blend_rule(a->rule), a->weight};
    for (const std::string& r : a->per_attribute) {
      const auto eq = r.find('=');
      require(eq != std::string::npos && eq > 0, "boolean: --attribute-rule " + r + ": expected NAME=RULE");
      o.rules[r.substr(0, eq)] = {cad::blend_rule(r.substr(eq + 1)), a->weight};
    }
    o.chordal_tolerance = a->tolerance;
    o.fuzzy = a->fuzzy;
    o.field = {a->field_degree, a->field_elements};
    const bool splitting = !a->split.empty();
    require(splitting ? a->b.empty() && a->op.empty() : !a->b.empty() && !a->op.empty(),
            "boolean: give either B and --op, or --split");
    const VModel ma = read_model(a->a, "boolean");
    cad::BooleanReport rep;
    VModel mb;
    VModel c;
    if (!splitting) {
      mb = read_model(a->b, "boolean");
      c = cad::boolean(ma, mb, cad::boolean_op(a->op), o, &rep);
    } else if (a->split.rfind("plane:", 0) == 0) {
      c = cad::split(ma, cad::parse_split_plane(a->split.substr(6)), o, &rep);
    } else {
      const std::vector<AnySpline> objects = io::read_spline_file(a->split);
      require(objects.size() == 1 && std::holds_alternative<TensorSpline<2>>(objects[0]),
              "boolean: --split " + a->split + ": expected one surface in the file, found " + std::to_string(objects.size()) + " objects");
      c = cad::split(ma, std::get<TensorSpline<2>>(objects[0]), o, &rep);
    }
    if (splitting) a->op = "split";
    io::write_vmodel(a->out, c);
    const ModelTessellation boundary = trimmed_boundary_mesh(c);
    const double va = ma.volume(), vb = splitting ? 0.0 : mb.volume(), vc = c.volume();
    const int chi = euler_characteristic(boundary.mesh);
    const bool closed = is_watertight(boundary.mesh);
    if (a->json) {
      nlohmann::json j{{"output", a->out},
                       {"operation", a->op},
                       {"cells", {{"a", rep.cells_a}, {"b", rep.cells_b}, {"result", rep.cells}}},
                       {"pieces", {{"all", rep.pieces}, {"a_only", rep.pieces_a_only}, {"b_only", rep.pieces_b_only}, {"both", rep.pieces_both}}},
                       {"volume", {{"a", va}, {"b", vb}, {"result", vc}}},
                       {"faces", {{"interior", rep.interior_faces}, {"boundary", rep.boundary_faces}}},
                       {"attributes", {{"exact", rep.exact_attributes}, {"fitted", rep.fitted_attributes}}},
                       {"boundary_mesh", {{"triangles", boundary.mesh.triangles.size()}, {"watertight", closed}, {"euler_characteristic", chi}}}};
      std::printf("%s\n", j.dump(2).c_str());
      return;
    }
    if (splitting) {
      std::printf("%s: split of %s (%d cells) by %s: %d cells (%d on the tool's side, %d on the other)\n", a->out.c_str(),
                  a->a.c_str(), rep.cells_a, a->split.c_str(), rep.cells, rep.pieces_both, rep.pieces_a_only);
      std::printf("volume: A %s, result %s\n", fmt(va).c_str(), fmt(vc).c_str());
    } else {
      std::printf("%s: %s of %s (%d cells) and %s (%d cells): %d cells from %d pieces (%d of A only, %d of B only, %d in both)\n",
                  a->out.c_str(), a->op.c_str(), a->a.c_str(), rep.cells_a, a->b.c_str(), rep.cells_b, rep.cells, rep.pieces,
                  rep.pieces_a_only, rep.pieces_b_only, rep.pieces_both);
      std::printf("volume: A %s, B %s, result %s\n", fmt(va).c_str(), fmt(vb).c_str(), fmt(vc).c_str());
    }
    std::printf("faces: %d between cells, %d on the boundary; boundary mesh %zu triangles, %s, Euler characteristic %d\n",
                rep.interior_faces, rep.boundary_faces, boundary.mesh.triangles.size(), closed ? "watertight" : "NOT watertight", chi);
    std::printf("attributes: %d carried or blended in closed form, %d fitted as fields\n", rep.exact_attributes, rep.fitted_attributes);
  });
}

}  // namespace trivar::cli
