#include "tspline_cli.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>

#include "cli.hpp"
#include "trivar/core/error.hpp"
#include "trivar/iga/refined_poisson.hpp"
#include "trivar/iga/solver.hpp"
#include "trivar/iga/surface_poisson.hpp"
#include "trivar/iga/t_mesh_space.hpp"
#include "trivar/iga/tensor_space.hpp"
#include "trivar/io/g2_format.hpp"
#include "trivar/io/lr_format.hpp"
#include "trivar/io/lr_g2_format.hpp"
#include "trivar/io/spline_file.hpp"
#include "trivar/io/step/step_file.hpp"
#include "trivar/io/stl_writer.hpp"
#include "trivar/io/t_spline_json.hpp"
#include "trivar/io/t_spline_vtk.hpp"
#include "trivar/io/tsm_format.hpp"
#include "trivar/model/triangle_mesh.hpp"
#include "trivar/tspline/bezier_patches.hpp"
#include "trivar/tspline/classification.hpp"
#include "trivar/tspline/lr_form.hpp"
#include "trivar/tspline/sharp_creases.hpp"
#include "trivar/tspline/t_mesh_patches.hpp"
#include "trivar/tspline/t_mesh_surface.hpp"
#include "trivar/tspline/t_mesh_tessellation.hpp"
#include "trivar/tspline/t_spline_surface.hpp"
#include "trivar/tspline/t_spline_tessellation.hpp"

namespace trivar::cli {

namespace {

bool is_t_spline_json(const std::string& path) {
  if (io::file_extension(path) != ".json") return false;
  std::ifstream in(path);
  if (!in.good()) return false;
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  return j.is_object() && j.value("kind", "") == "t_spline";
}

// A T-spline as read: the three layers when the file has them, always the evaluator.
struct Loaded {
  std::string format;
  std::optional<TSpline> layers;
  std::optional<io::TsmReport> tsm;
  std::string step_type;  // Part 42 locally_refined_spline_type when read from that form
  std::unique_ptr<TSplineSurface> surface;  // empty for a TSM model with star points
  std::unique_ptr<TMeshSurface> mesh;       // a TSM model without a global (s, t): evaluated per face
  std::unique_ptr<TMesh> tsm_mesh;          // a TSM model with one: its mesh (for surface analysis)
};

Loaded load(const std::string& path) {
  Loaded l;
  const std::string ext = io::file_extension(path);
  if (ext == ".tsm") {
    io::TsmModel m = io::read_tsm(path);
    l.format = "TSM #TS0200";
    l.tsm = std::move(m.report);
    if (m.spline.image.faces.empty()) {  // star points or a closed strip of faces
      try {
        l.mesh = std::make_unique<TMeshSurface>(m.mesh);
      } catch (const Error& e) {
        throw Error(path + ": " + e.what());
      }
      return l;
    }
    l.layers = std::move(m.spline);
    l.tsm_mesh = std::make_unique<TMesh>(std::move(m.mesh));
  } else if (is_t_spline_json(path)) {
    l.format = "trivar T-spline JSON";
    l.layers = io::read_t_spline_json(path);
  } else {
    io::step::StepContents c = io::step::read_step(path);
    require(!c.t_splines.empty(), path + ": no T-spline in the file");
    if (c.t_splines.size() > 1)
      std::fprintf(stderr, "trivar: %s holds %zu T-splines; using the first\n", path.c_str(), c.t_splines.size());
    io::step::StepTSpline& t = c.t_splines.front();
    l.format = "STEP " + t.entity;
    if (t.layers) {
      l.layers = std::move(*t.layers);
    } else {
      l.step_type = t.type;
      l.surface = std::make_unique<TSplineSurface>(t.degrees, std::move(t.basis));
    }
  }
  if (!l.surface) l.surface = std::make_unique<TSplineSurface>(*l.layers);
  return l;
}

void write_triangulation(const std::string& out, const TSplineTriangulation& m, double tol) {
  const std::string ext = io::file_extension(out);
  if (ext == ".vtu") {
    io::write_triangulation_vtu(out, m);
  } else if (ext == ".obj") {
    io::write_triangulation_obj(out, m);
  } else {
    TriangleMesh t;
    t.vertices = m.points;
    t.triangles = m.triangles;
    io::write_stl(out, t);
  }
  std::printf("%s: %zu triangles, chordal tolerance %s\n", out.c_str(), m.triangles.size(), fmt(tol).c_str());
}

// Fusion 360's settings of a TSM file (none in Rhino's).
std::string fusion_settings(const io::TsmReport& r) {
  if (r.end_conditions.empty() && r.star_knot_rule.empty() && r.behavior_version.empty()) return {};
  std::string s = "end conditions " + (r.end_conditions.empty() ? std::string("(none)") : r.end_conditions);
  if (!r.star_knot_rule.empty()) s += ", star knot rule " + r.star_knot_rule;
  if (!r.cap_type.empty()) s += ", cap type " + r.cap_type;
  s += ", version " + std::to_string(r.version);
  if (!r.behavior_version.empty()) s += ", behavior version " + r.behavior_version;
  if (!r.compat_version.empty()) s += ", compat version " + r.compat_version;
  if (!r.grip_map) s += "; no grip map (one control point per vertex)";
  return s;
}

void add_fusion_settings(nlohmann::json& j, const io::TsmReport& r) {
  if (fusion_settings(r).empty()) return;
  j["fusion"] = {{"end_conditions", r.end_conditions}, {"star_knot_rule", r.star_knot_rule}, {"cap_type", r.cap_type},
                 {"version", r.version}, {"behavior_version", r.behavior_version},
                 {"compat_version", r.compat_version}, {"grip_map", r.grip_map}};
}

}  // namespace

bool is_t_spline_file(const std::string& path) {
  const std::string ext = io::file_extension(path);
  if (ext == ".tsm") return true;
  if (ext == ".json") return is_t_spline_json(path);
  if (!is_step_file(path)) return false;
  // A scan of the text, not a parse: B-rep files stay on the STEP path at the cost of one read.
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return text.find("T_SPLINE_SURFACE(") != std::string::npos || text.find("_T_SPLINE.") != std::string::npos;
}

// Fusion's crease lists (100edges, 100verts) as read: kept and written back.
void add_crease_lists(nlohmann::json& j, const TMesh& m) {
  if (m.crease_edges.empty() && m.crease_vertices.empty()) return;
  j["crease_edges"] = m.crease_edges;
  j["crease_vertices"] = m.crease_vertices;
}

void print_crease_lists(const TMesh& m) {
  if (m.crease_edges.empty() && m.crease_vertices.empty()) return;
  std::printf("  creases listed (100edges, 100verts): %zu edges, %zu vertices%s\n", m.crease_edges.size(), m.crease_vertices.size(),
              m.end_conditions == EndConditions::subd_creases ? " (sharp creases and corners)" : "");
}

// A T-mesh without a global (s, t) (star points, a closed strip of faces): faces by evaluation method, the star
// points, the continuity the methods give.
void print_mesh_info(const std::string& path, const Loaded& l, bool json) {
  const TMeshSurface& s = *l.mesh;
  const io::TsmReport& r = *l.tsm;
  const CreaseSingularities ends = crease_singularities(s.mesh());
  const int darts = static_cast<int>(ends.darts.size()), cones = static_cast<int>(ends.cone_points.size());
  // The star points of the mesh as evaluated: the cut-open mesh's irregular vertices but the darts (slit ends).
  std::vector<int> stars;
  std::copy_if(s.stars().begin(), s.stars().end(), std::back_inserter(stars),
               [&](int v) { return std::find(ends.darts.begin(), ends.darts.end(), v) == ends.darts.end(); });
  std::map<int, int> valences;
  for (int v : stars) ++valences[s.valence(v)];
  const int nu = s.count(FaceMethod::non_uniform);
  const int bs = s.boundary_star_faces();
  const int sub = s.count(FaceMethod::subdivided);
  const int cr = s.count(FaceMethod::crease);
  const int avg = s.count(FaceMethod::averaging);
  // Local subdivision serves the irregular vertices of a crease boundary, or in a mesh without one close star points.
  const bool subd_creases = s.source_mesh().end_conditions == EndConditions::subd_creases;
  const int faces = s.count(FaceMethod::exact) + s.count(FaceMethod::bicubic) + s.count(FaceMethod::star) + nu + sub + cr + avg;
  const bool creases = r.crease_edges > 0 || cones > 0;
  std::string continuity = s.mesh().degree == 1 ? "C0 across every edge (degree 1: each face bilinear pieces, star points or not)"
                           : stars.empty()     ? "C2 across every edge"
                           : avg > 0 ? "C" + std::to_string(s.mesh().degree - 1) + " across every edge away from star points; C1 across the edges at a star point; G1 at star points (averaging subdivision, measured)"
                                               : "C2 across every edge away from star points; C1 across the edges at a star point; G1 at star points";
  if (creases) continuity += " but the sharp creases, C0 across those";
  if (darts > 0) continuity += "; C1 across the edges at a dart, G1 at the dart";
  if (cones > 0) continuity += "; no tangent plane at the cone points";
  const char* kind = r.crease_edges > 0 ? "T-spline surface with sharp creases"
                   : creases ? "T-spline surface with cone points"
                   : stars.empty() ? "T-spline surface with a closed strip of faces"
                                       : "T-spline surface with star points";
  nlohmann::json j{{"file", path}, {"kind", kind}, {"format", l.format},
                   {"degrees", {s.mesh().degree, s.mesh().degree}}, {"units", r.units}, {"faces", faces},
                   {"star_points", r.star_points}, {"crease_edges", r.crease_edges}, {"darts", darts}, {"cone_points", cones},
                   {"faces_exact", s.count(FaceMethod::exact)},
                   {"faces_catmull_clark", s.count(FaceMethod::bicubic) + s.count(FaceMethod::star) + sub},
                   {"faces_at_star_points", s.count(FaceMethod::star)}, {"faces_at_boundary_star_points", bs},
                   {"faces_non_uniform_catmull_clark", nu}, {"faces_subdivided", sub}, {"faces_crease_subdivision", cr},
                   {"faces_averaging_subdivision", avg},
                   {"non_uniform_star_points", s.non_uniform_stars()}, {"global_steps", s.global_steps()},
                   {"t_junction_lines", s.completed_lines() ? s.completed_lines()->lines : 0},
                   {"faces_as_given", static_cast<int>(s.source_mesh().faces.size())}, {"continuity", continuity},
                   {"deleted_slots", r.deleted}, {"deleted_faces", r.holes}, {"skipped_records", r.skipped_records}};
  for (const auto& [n, c] : valences) j["star_valences"][std::to_string(n)] = c;
  add_fusion_settings(j, r);
  add_crease_lists(j, s.source_mesh());
  if (json) {
    std::printf("%s\n", j.dump(2).c_str());
    return;
  }
  std::string vs;
  for (const auto& [n, c] : valences) vs += (vs.empty() ? "" : ", ") + std::to_string(c) + " of valence " + std::to_string(n);
  std::printf("%s: %s (%s), degree %d%s\n", path.c_str(), kind, l.format.c_str(), s.mesh().degree,
              r.units.empty() ? "" : (", units " + r.units).c_str());
  if (const std::string f = fusion_settings(r); !f.empty()) std::printf("  Fusion 360: %s\n", f.c_str());
  if (creases)
    std::printf("  %d faces, %d sharp crease edges (listed in 100edges or ec between two faces: infinitely sharp subdivision creases), %d star "
                "points (%zu%s%s after the mesh is cut open along the creases, each side a crease boundary); faces are "
                "evaluated in their own (u, v)\n", faces, r.crease_edges, r.star_points, stars.size(),
                vs.empty() ? "" : ": ", vs.c_str());
  else if (stars.empty())
    std::printf("  %d faces, no star point; a closed strip of faces (a torus, a tube) leaves no global (s, t): faces are "
                "evaluated in their own (u, v)\n", faces);
  else
    std::printf("  %d faces, %d star points (%s); no global (s, t): faces are evaluated in their own (u, v)\n", faces,
                r.star_points, vs.c_str());
  if (darts > 0 || cones > 0)
    std::printf("  %d dart%s (a crease ending inside the mesh: the smooth rule there, the crease a slit up to it) and %d cone "
                "point%s (a creased vertex inside the mesh on no crease: interpolated, no tangent plane)\n", darts,
                darts == 1 ? "" : "s", cones, cones == 1 ? "" : "s");
  if (const CompletedLines* c = s.completed_lines())
    std::printf("  %d T-junction line%s near star points%s completed first (%d vertices inserted by knot insertion along the rows "
                "crossed; the T-spline unchanged where it is one): the %zu faces as given are %zu faces%s\n", c->lines,
                c->lines == 1 ? "" : "s", creases || subd_creases ? " or irregular crease vertices" : "", c->vertices,
                s.source_mesh().faces.size(), c->pieces.size(),
                s.global_steps() > 0 ? "" : " (eval takes the faces as given; written back as given)");
  if (s.global_steps() > 0)
    std::printf("  refined first by %d global non-uniform Catmull-Clark steps (star points fewer than %d edges apart with "
                "unequal knot intervals; the limit surface is unchanged): each of the %zu faces %s is %d x %d faces, "
                "and the faces counted are the refined mesh's (eval takes the faces as given; written back as given)\n", s.global_steps(),
                TMeshSurface::kStarsApart, s.face_mesh().faces.size() >> (2 * s.global_steps()),
                s.completed_lines() ? "after the lines" : "as given", 1 << s.global_steps(), 1 << s.global_steps());
  if (stars.empty() && creases)
    std::printf("  %d faces exact (the T-spline of their side in a chart of their neighbourhood), %d the bicubic B-spline "
                "cell of their 16 points (round closed strips of a side)\n", s.count(FaceMethod::exact), s.count(FaceMethod::bicubic));
  else if (stars.empty())
    std::printf("  %d faces exact (the T-spline in a chart of their neighbourhood, not wrapping round the strip), %d "
                "the bicubic B-spline cell of their 16 points (round strips too short for such charts)\n",
                s.count(FaceMethod::exact), s.count(FaceMethod::bicubic));
  else if (s.global_steps() > 0)
    std::printf("  %d faces by the Catmull-Clark limit surface (%d at a star point, evaluated exactly by subdivision; the "
                "others bicubic B-spline cells on their knots, the T-spline)\n",
                s.count(FaceMethod::exact) + s.count(FaceMethod::bicubic) + s.count(FaceMethod::star) + sub, s.count(FaceMethod::star));
  else if (avg > 0)
    std::printf("  %d faces exact (the T-spline in a chart of their neighbourhood), %d faces within %d rings of a star "
                "point by the degree-%d averaging subdivision (linear subdivision and %d averaging passes per step: the uniform "
                "B-spline where the mesh is a regular grid, evaluated by local subdivision)\n",
                s.count(FaceMethod::exact), avg, s.mesh().degree + 2, s.mesh().degree, (s.mesh().degree - 1) / 2);
  else
    std::printf("  %d faces exact (the T-spline in a chart of their neighbourhood), %d faces within %d rings of a star "
                "point by the Catmull-Clark limit surface (%d at a star point, evaluated exactly by subdivision)\n",
                s.count(FaceMethod::exact), s.count(FaceMethod::bicubic) + s.count(FaceMethod::star) + sub, s.mesh().degree + 2,
                s.count(FaceMethod::star));
  if (nu > 0)
    std::printf("  %d faces around %d star points with unequal knot intervals by non-uniform Catmull-Clark (knot-interval "
                "weighted rules, exact B-spline cells per subdivision level; C2 away from the star point, its tangent "
                "plane reached in the limit, slowly for large interval ratios)\n", nu, s.non_uniform_stars());
  if (sub > 0)
    std::printf("  %d of them with several star corners or at star points joined by an edge, through one local "
                "Catmull-Clark step (each quarter a bicubic or Stam patch of the subdivided points)\n", sub);
  if (cr > 0 && subd_creases)
    std::printf("  %d faces within %d rings of irregular vertices of a crease boundary (a crease turning, a star point on "
                "it, a corner with a side of several faces, a dart, a cone point) by repeated local Catmull-Clark subdivision with the crease "
                "rules (exact; the limit position at the vertex itself)\n", cr, s.mesh().degree + 1);
  else if (cr > 0)
    std::printf("  %d faces near star points with unequal knot intervals (several star corners, star points within three "
                "rings of each other, star points on or near a Bezier boundary) by repeated local non-uniform Catmull-Clark subdivision "
                "(exact; the limit position and tangent plane at the star point itself)\n", cr);
  if (bs > 0)
    std::printf("  %d faces at star points on the boundary by Catmull-Clark of the control mesh extended by a ghost layer "
                "(the T-spline's Bezier end condition where regular, on its knot intervals; boundary curve the cubic B-spline "
                "of the block points from two faces along the boundary on)\n", bs);
  std::printf("  continuity: %s\n", continuity.c_str());
  print_crease_lists(s.source_mesh());
  if (!r.skipped_records.empty()) {
    std::string k;
    for (const auto& [name, n] : r.skipped_records) k += (k.empty() ? "" : ", ") + name + " x" + std::to_string(n);
    std::printf("  records without geometry (skipped): %s\n", k.c_str());
  }
}

void print_tspline_info(const std::string& path, bool json) {
  const Loaded l = load(path);
  if (l.mesh) return print_mesh_info(path, l, json);
  const TSplineSurface& surf = *l.surface;
  const PartitionOfUnity& pu = surf.partition_of_unity();
  const Box<2> dom = surf.domain();
  nlohmann::json j{{"file", path},
                   {"kind", "T-spline surface"},
                   {"format", l.format},
                   {"degrees", {surf.degrees()[0], surf.degrees()[1]}},
                   {"domain", {{dom.lo[0], dom.hi[0]}, {dom.lo[1], dom.hi[1]}}},
                   {"blending_functions", surf.basis().size()},
                   {"bezier_elements", surf.elements().size()},
                   {"partition_of_unity", {{"min_sum", pu.min_sum}, {"max_sum", pu.max_sum},
                                           {"max_defect", pu.max_defect}, {"elements_off", pu.elements_off},
                                           {"sampled_min", pu.sampled_min}, {"sampled_max", pu.sampled_max}}}};
  if (!l.step_type.empty()) j["part42_type"] = l.step_type;
  std::optional<TSplineClass> cls;
  std::string as;
  if (l.layers) {
    const TSpline& ts = *l.layers;
    cls = classify(ts, surf);
    as = cls->analysis_suitable ? "yes" : "no";
    j["t_image"] = {{"vertices", ts.image.vertices.size()}, {"edges", ts.image.edges.size()},
                    {"links", ts.image.links.size()}, {"faces", ts.image.faces.size()},
                    {"edge_conditions", ts.image.conditions.size()}};
    j["t_connect"] = {{"nodes", ts.connect.nodes.size()}};
    j["t_pointset"] = {{"points", ts.pointset.points.size()}};
    j["classification"] = {{"t_junctions", cls->t_junctions}, {"gap_t_junctions", cls->gap_junctions},
                           {"analysis_suitable", as},
                           {"crossing_extensions", cls->crossing_extensions},
                           {"dual_compatible", cls->dual.compatible},
                           {"dual_incompatible_pairs", cls->dual.failing_pairs},
                           {"rectangular_domain", cls->rectangular_domain}, {"standard", cls->standard},
                           {"semi_standard", cls->semi_standard},
                           {"linear_independence", to_string(cls->independence)},
                           {"part42_type", cls->part42_type()}};
  }
  if (l.tsm) {
    const io::TsmReport& r = *l.tsm;
    j["units"] = r.units;
    j["star_points"] = r.star_points;
    j["deleted_slots"] = r.deleted;
    j["deleted_faces"] = r.holes;
    j["repeated_knot_nodes"] = r.repeated_knot_nodes;
    j["skipped_records"] = r.skipped_records;
    add_fusion_settings(j, r);
    add_crease_lists(j, *l.tsm_mesh);
  }
  if (json) {
    std::printf("%s\n", j.dump(2).c_str());
    return;
  }
  std::printf("%s: T-spline surface (%s), degrees %d x %d%s\n", path.c_str(), l.format.c_str(), surf.degrees()[0],
              surf.degrees()[1], l.tsm && !l.tsm->units.empty() ? (", units " + l.tsm->units).c_str() : "");
  if (l.tsm)
    if (const std::string f = fusion_settings(*l.tsm); !f.empty()) std::printf("  Fusion 360: %s\n", f.c_str());
  if (l.layers) {
    const TSpline& ts = *l.layers;
    std::printf("  T-image: %zu vertices, %zu edges, %zu links, %zu faces, %zu edge conditions\n",
                ts.image.vertices.size(), ts.image.edges.size(), ts.image.links.size(), ts.image.faces.size(),
                ts.image.conditions.size());
    std::printf("  T-connect: %zu nodes; T-pointset: %zu points\n", ts.connect.nodes.size(), ts.pointset.points.size());
  } else {
    std::printf("  blending functions only (Part 42 type %s): %zu\n", l.step_type.c_str(), surf.basis().size());
  }
  if (l.tsm)
    std::printf("  TSM: %d repeated-knot nodes (Bezier end conditions), %d deleted faces, %d deleted slots, %d star points\n",
                l.tsm->repeated_knot_nodes, l.tsm->holes, l.tsm->deleted, l.tsm->star_points);
  std::printf("  domain [%s, %s] x [%s, %s], %zu Bezier elements\n", fmt(dom.lo[0]).c_str(), fmt(dom.hi[0]).c_str(),
              fmt(dom.lo[1]).c_str(), fmt(dom.hi[1]).c_str(), surf.elements().size());
  std::printf("  partition of unity: sum of blending functions from %s to %s (sampled; Bezier bound [%s, %s]), "
              "off 1 on %d element%s (evaluated as sum w P B / sum w B)\n",
              fmt(pu.sampled_min).c_str(), fmt(pu.sampled_max).c_str(), fmt(pu.min_sum).c_str(), fmt(pu.max_sum).c_str(),
              pu.elements_off, pu.elements_off == 1 ? "" : "s");
  if (cls)
    std::printf("  classification: %d T-junctions%s, analysis-suitable %s (%d crossing extensions, dual-compatible %s%s), "
                "standard %s, semi-standard %s, blending functions %s; Part 42 type %s\n",
                cls->t_junctions,
                cls->gap_junctions ? (" (" + std::to_string(cls->gap_junctions) + " facing each other across gaps no ray crosses: no extension)").c_str() : "",
                as.c_str(), cls->crossing_extensions, cls->dual.compatible ? "yes" : "no",
                cls->rectangular_domain ? "" : "; the domain is not a rectangle", cls->standard ? "yes" : "no",
                cls->semi_standard ? "yes" : "no", to_string(cls->independence), cls->part42_type().c_str());
  if (l.tsm_mesh) print_crease_lists(*l.tsm_mesh);
  if (l.tsm && !l.tsm->skipped_records.empty()) {
    std::string s;
    for (const auto& [k, n] : l.tsm->skipped_records) s += (s.empty() ? "" : ", ") + k + " x" + std::to_string(n);
    std::printf("  records without geometry (skipped): %s\n", s.c_str());
  }
}

void eval_tspline(const std::string& path, const std::vector<double>& params, int order) {
  require(order <= 1, "eval: T-splines evaluate first derivatives at most (--derivs 0 or 1), got " + std::to_string(order));
  const Loaded l = load(path);
  if (l.mesh) {
    require(params.size() == 3 && params[0] == std::floor(params[0]),
            "eval: " + path + " has no global (s, t) (star points, a closed strip of faces or sharp creases): give FACE U V (u, v in [0, 1] on the face)");
    // The file's face ids, also after global steps refined the mesh.
    const int face = static_cast<int>(params[0]);
    require(face >= 0 && static_cast<std::size_t>(face) < l.mesh->source_mesh().faces.size() &&
                l.mesh->method(l.mesh->refined_point(face, 0, 0).face) != FaceMethod::none,
            "eval: " + path + " has no face " + fmt(params[0]));
    require(params[1] >= 0 && params[1] <= 1 && params[2] >= 0 && params[2] <= 1,
            "eval: (u, v) = (" + fmt(params[1]) + ", " + fmt(params[2]) + ") is outside the face's [0, 1]^2");
    double out[9];
    l.mesh->eval_source(face, params[1], params[2], out);
    std::printf("S   = %s\n", fmt(out, 3).c_str());
    if (order == 1) {
      std::printf("S_u = %s\n", fmt(out + 3, 3).c_str());
      std::printf("S_v = %s\n", fmt(out + 6, 3).c_str());
    }
    std::printf("face %d: %s\n", face, face_method_name(l.mesh->method(face)));
    return;
  }
  require(params.size() == 2, "eval: a T-spline surface takes 2 parameters, got " + std::to_string(params.size()));
  const TSplineSurface& surf = *l.surface;
  const Param<2> u{params[0], params[1]};
  require(surf.locate(u) >= 0, "eval: (" + fmt(u[0]) + ", " + fmt(u[1]) + ") is outside the T-spline's faces (domain [" +
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

void convert_tspline(const std::string& in, const std::string& out, const TSplineConvertOptions& o) {
  require(o.step_form == "t-spline" || o.step_form == "part42",
          "convert: --step-form is t-spline or part42, not '" + o.step_form + "'");
  const Loaded l = load(in);
  const std::string ext = io::file_extension(out);
  if (l.mesh) {
    if (ext == ".tsm") {
      io::write_tsm(out, l.mesh->source_mesh(), *l.tsm);
      return;
    }
    if (ext == ".g2" || ext == ".json" || ext == ".xml" || is_step_file(out)) {
      // Bezier patches: exact away from the corners at the star points, those within the tolerance.
      TMeshPatchOptions po;
      po.tolerance = o.tolerance;
      const TMeshPatches p = t_mesh_patches(*l.mesh, po);
      std::vector<AnySpline> patches;
      for (const FacePatch& f : p.patches) patches.emplace_back(f.surface);
      if (is_step_file(out))
        io::step::write_step(out, patches, {});
      else
        io::write_spline_file(out, patches);
      const bool crease_corners = l.mesh->count(FaceMethod::crease) > 0 && l.mesh->source_mesh().end_conditions == EndConditions::subd_creases;
      const bool cones = !crease_singularities(l.mesh->mesh()).cone_points.empty();
      bool cells = false;  // corner patches beside B-spline cells of unequal intervals meet them within the tolerance
      for (int f = 0; f < l.mesh->num_faces(); ++f) cells = cells || (l.mesh->method(f) == FaceMethod::crease && l.mesh->crease_face(f).has_cells());
      // Averaging faces' corner patches interpolate the limit surface: C0 with their neighbours within the tolerance.
      const bool averaging = l.mesh->count(FaceMethod::averaging) > 0;
      std::printf("%s: %zu Bezier patches (%d exact, %d corner patches at star points%s after %d subdivision levels, "
                  "%s from the limit surface, tolerance %s); C0%s, %s\n",
                  out.c_str(), p.patches.size(), p.exact_patches, p.corner_patches,
                  crease_corners ? " and irregular crease vertices" : "", p.levels, fmt(p.deviation).c_str(),
                  fmt(p.tolerance).c_str(),
                  cells || averaging ? " (within the tolerance where corner patches meet the exact pieces beside them)" : "",
                  (averaging ? "degree " + std::to_string(l.mesh->mesh().degree) + " (the corner patches interpolate the limit surface)"
                             : std::string("G1 at star points") + (cones ? " (not at the cone points: no tangent plane)" : ""))
                      .c_str());
      return;
    }
    require(ext == ".stl" || ext == ".obj" || ext == ".vtu",
            "convert: " + in + " has no global (s, t) (star points, a closed strip of faces or sharp creases); it converts to .tsm, to Bezier patches (.g2, .json, .xml, .stp), or to .stl, .obj or .vtu triangles, not '" + ext + "'");
    double tol = o.tolerance;
    if (tol <= 0) {
      Box<3> b = Box<3>::empty();
      for (const RationalPoint& p : l.mesh->mesh().points) b.extend(p.xyz.data());
      tol = 1e-3 * b.diagonal();
    }
    write_triangulation(out, tessellate(*l.mesh, tol), tol);
    return;
  }
  const TSplineSurface& surf = *l.surface;
  if (is_step_file(out)) {
    require(l.layers.has_value(), "convert: " + in + " holds the blending functions only; it converts to Part 42 STEP, .lr, .vtu, .stl or .obj");
    const auto form = o.step_form == "part42" ? io::step::TSplineStepForm::part42 : io::step::TSplineStepForm::t_spline_entities;
    io::step::write_t_spline_step(out, *l.layers, form);
    std::printf("%s: T-spline as %s\n", out.c_str(),
                o.step_form == "part42" ? "an ISO 10303-42 locally refined surface" : "T_SPLINE_SURFACE entities (AP238)");
    return;
  }
  if (ext == ".lr") {
    std::string why;
    auto lr = lr_form(surf, why);
    require(lr.has_value(), "convert: " + in + " is not an LR spline (" + why + ")");
    io::write_lr(out, {AnyLRSpline(std::move(*lr))});
    return;
  }
  if (ext == ".g2") {
    // GoTools reads both: the LR spline (exact, one object) when the blending functions form one, else one
    // rational Bezier patch per element.
    std::string why;
    if (auto lr = lr_form(surf, why)) {
      io::write_lr_g2(out, {AnyLRSpline(std::move(*lr))});
      std::printf("%s: GoTools LRSplineSurface\n", out.c_str());
      return;
    }
    std::vector<AnySpline> patches;
    for (TensorSpline<2>& p : bezier_patches(surf)) patches.emplace_back(std::move(p));
    io::write_g2(out, patches);
    std::printf("%s: %zu rational Bezier patches (SplineSurface; not an LR spline: %s)\n", out.c_str(), patches.size(),
                why.c_str());
    return;
  }
  if (ext == ".tsm") {
    require(l.layers.has_value(), "convert: " + in + " holds the blending functions only; .tsm needs the three layers");
    // A Fusion 360 file keeps its mesh and settings; others are written from the T-spline's layers.
    if (l.tsm_mesh && !fusion_settings(*l.tsm).empty())
      io::write_tsm(out, *l.tsm_mesh, *l.tsm);
    else
      io::write_tsm(out, *l.layers);
    return;
  }
  if (ext == ".json") {
    require(l.layers.has_value(), "convert: " + in + " holds the blending functions only; the JSON form needs the three layers");
    io::write_t_spline_json(out, *l.layers);
    return;
  }
  require(ext == ".vtu" || ext == ".stl" || ext == ".obj",
          "convert: a T-spline converts to .stp/.step, .tsm, .lr, .g2, .json, .vtu, .stl or .obj, not '" + ext + "'");
  if (ext == ".vtu" && !o.triangles) {
    io::write_t_spline_vtu(out, surf);
    return;
  }
  double tol = o.tolerance;
  if (tol <= 0) {
    Box<3> b = Box<3>::empty();
    for (const auto& e : surf.bezier_elements())
      for (std::size_t i = 0; i < e.coefs.size(); i += 4) {
        const double x[3] = {e.coefs[i] / e.coefs[i + 3], e.coefs[i + 1] / e.coefs[i + 3], e.coefs[i + 2] / e.coefs[i + 3]};
        b.extend(x);
      }
    tol = 1e-3 * b.diagonal();
  }
  write_triangulation(out, tessellate(surf, tol), tol);
}

namespace {

// A planar T-mesh with star points: the C0 multipatch space of its face patches (cut until their sides conform),
// each patch refine x refine elements.
void solve_t_mesh_poisson(const std::string& path, const TMeshSurface& mesh, const std::string& solver,
                          const std::string& vtu, int threads, int refine) {
  Box<3> box = Box<3>::empty();
  for (const RationalPoint& p : mesh.mesh().points) box.extend(p.xyz.data());
  if (box.extent(2) > 1e-12 * box.diagonal()) {
    // A curved surface: the Laplace-Beltrami problem on it (a closed one with a reaction term).
    require(vtu.empty(), "solve: " + path + ": --out is written for planar meshes only (the solution of a curved one is a field on the surface)");
    TMeshSpaceReport rep;
    TMeshSurfaceSpace space;
    try {
      space = t_mesh_surface_space(mesh, refine, &rep);
    } catch (const Error& e) {
      throw Error("solve: " + path + ": " + e.what());
    }
    SurfacePoissonProblem pb;
    pb.source = [](const double*) { return 1.0; };
    const bool closed = space.space.boundary.empty();
    pb.reaction = closed ? 1.0 : 0.0;
    auto s = make_solver(solver);
    const SurfacePoissonResult r = solve_surface_poisson(space, pb, *s);
    std::printf("T-mesh surface (curved, %s): -lap_S u%s = 1%s; %d faces as %d patches, %d corner patches at star points (%s "
                "from the limit surface), %d x %d bicubic elements per patch, %d functions, %d unknowns\n",
                closed ? "closed" : "open", closed ? " + u" : "", closed ? "" : ", u = 0 on the boundary", rep.faces,
                rep.patches, rep.corner_patches, fmt(rep.deviation).c_str(), refine, refine, space.space.num_basis, r.dofs);
    std::printf("area %s\nu: max %s\n", fmt(r.area).c_str(), fmt(r.coefs.maxCoeff()).c_str());
    return;
  }
  TMeshSpaceReport rep;
  MultipatchSpace<2> space;
  try {
    space = t_mesh_space(mesh, refine, &rep);
  } catch (const Error& e) {
    throw Error("solve: " + path + ": " + e.what());
  }
  PoissonProblem<2> pb;
  pb.source = [](const double*) { return 1.0; };
  pb.dirichlet.push_back({space.boundary, {}, nullptr});
  auto s = make_solver(solver);
  const SolveResult r = solve_poisson(space, pb, *s, threads);
  std::printf("T-mesh multipatch space (C0 across faces): %d faces as %d patches (Bezier elements, cut where T-junctions "
              "put corners inside sides), %d corner patches at star points (%s from the limit surface), %d x %d bicubic "
              "elements per patch, %d functions\n",
              rep.faces, rep.patches, rep.corner_patches, fmt(rep.deviation).c_str(), refine, refine, space.num_basis);
  std::printf("dofs %d, assembly %.3f s, solve %.3f s\n", r.dofs, r.assembly_seconds, r.solve_seconds);
  std::printf("u: max %s\n", fmt(r.coefs.maxCoeff()).c_str());
  if (vtu.empty()) return;
  // The solution as surfaces (x, y, u) on the patches' own functions.
  std::vector<AnySpline> out;
  for (int p = 0; p < space.num_patches(); ++p) {
    const TensorSpline<2>& g = space.patches[static_cast<std::size_t>(p)].geometry;
    std::vector<double> c;
    for (int i = 0; i < g.num_coefs(); ++i) {
      const double* q = g.coef(i);
      const double w = g.weight(i);
      c.insert(c.end(), {q[0], q[1], w * r.coefs[space.global[static_cast<std::size_t>(p)][static_cast<std::size_t>(i)]]});
      if (g.is_rational()) c.push_back(w);
    }
    out.emplace_back(TensorSpline<2>(g.knot_vectors(), 3, g.is_rational(), std::move(c)));
  }
  io::write_spline_file(vtu, out);
}

}  // namespace

void solve_tspline_poisson(const std::string& path, const std::string& solver, const std::string& vtu, int threads,
                           int refine) {
  const Loaded l = load(path);
  if (l.mesh) return solve_t_mesh_poisson(path, *l.mesh, solver, vtu, threads, refine);
  const TSplineSurface& surf = *l.surface;
  if (l.tsm_mesh) {
    // A curved TSM model: the surface problem on its faces' patches.
    bool planar = true;
    for (const LRBSpline<2>& b : surf.basis()) planar = planar && b.coef[2] == 0;
    if (!planar) {
      std::unique_ptr<TMeshSurface> mesh;
      try {
        mesh = std::make_unique<TMeshSurface>(*l.tsm_mesh, threads);
      } catch (const Error& e) {
        throw Error("solve: " + path + ": " + e.what());
      }
      return solve_t_mesh_poisson(path, *mesh, solver, vtu, threads, refine);
    }
  }
  RefinedSpace<2> space;
  try {
    space = refined_space(surf, threads);
  } catch (const Error& e) {
    throw Error("solve: " + path + ": " + e.what());
  }
  PoissonProblem<2> pb;
  pb.source = [](const double*) { return 1.0; };
  pb.dirichlet.push_back({all_faces<2>(), {}, nullptr});
  auto s = make_solver(solver);
  const SolveResult r = solve_poisson(space, pb, *s, threads);
  std::printf("T-spline space: %d blending functions, %d Bezier elements, degrees %d x %d\n", space.num_basis,
              space.num_elements(), space.degrees[0], space.degrees[1]);
  // The solution as the surface (x, y, u) on the same blending functions.
  std::vector<LRBSpline<2>> basis(surf.basis().begin(), surf.basis().end());
  for (std::size_t i = 0; i < basis.size(); ++i) basis[i].coef[2] = r.coefs[static_cast<Eigen::Index>(i)];
  const TSplineSurface field(surf.degrees(), std::move(basis), threads);
  const Box<2> dom = surf.domain();
  double c[3];
  field.eval({0.5 * (dom.lo[0] + dom.hi[0]), 0.5 * (dom.lo[1] + dom.hi[1])}, c);
  std::printf("dofs %d, assembly %.3f s, solve %.3f s\n", r.dofs, r.assembly_seconds, r.solve_seconds);
  std::printf("u at the domain centre: %s at (x, y) = (%s, %s)\n", fmt(c[2]).c_str(), fmt(c[0]).c_str(),
              fmt(c[1]).c_str());
  if (!vtu.empty()) io::write_t_spline_vtu(vtu, field);
}

}  // namespace trivar::cli
