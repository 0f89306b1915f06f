#pragma once
// The Rhino T-Splines text format (.tsm, header #TS0200), read into the three T-spline layers. One record per
// line, numbered per kind from 0 in file order; a bare keyword is a deleted slot that keeps its number; '#'
// starts a comment. Settings: degree, cap-type, star-smoothness, units <scale> <name>,
// force-bezier-end-conditions, tol, ver. Topology as half-edges:
//   f L flag                 face, L one of its links
//   e L d                    edge, L one of its two links, d its knot interval
//   v L DIR                  vertex, L an outgoing link, DIR its direction in the vertex's own frame
//   l prev next opp v f e c  link leaving vertex v along edge e in face f (-1: outside); c = (angle of f at
//                            v) / 90 - 1: 0 corner, 1 straight (a T-junction side), 2 reflex
//   ec e bc                  edge condition
// Control points (grips) `0g x y z w` with the grip map `0m gvp v` / `0m gv v` (one per grip: its vertex; gvp
// the vertex's own node) and `0m cg v 4 dN dW dS dE grips...` (Bezier end conditions: the repeated-knot node
// block at v, dK layers towards direction K of the vertex frame, listed as four wedges K = N, W, S, E of
// dK x (dK+1 + 1) grips, -1: none). Other records (editor state: 100001uv, 100001uvr, 50000grip, symmetry
// 105sym/105plane/105a) carry no geometry: they are counted and reported, as is any unknown record.
//
// Autodesk Fusion 360 (TSplineBody.saveAsTSMFile) writes the same records with other settings: cap-type G1CAPS,
// `end-conditions MULTIPLE_KNOTS` (Bezier end conditions) or `SUBD_CREASES` (the boundary as a subdivision
// crease) instead of force-bezier-end-conditions, `star-knot-rule NURCCS` (knot-interval-weighted Catmull-Clark
// at star points), and after the grips geom-tol, behavior-version and compat-version. Without `0m` records
// each vertex has one grip: the `0g` records in vertex order (one per vertex slot, a deleted vertex's a bare
// `0g`, or one per live vertex). `106ek` records that repeat the edges' knot intervals (-1 for a deleted edge),
// and 50000grip carry no geometry; `100edges` / `100verts` list the creased edges and vertices (Fusion's crease
// lists, kept as TMesh::crease_edges / crease_vertices and written back; in Rhino's files editor selections,
// skipped). Other edge knots, end conditions or star rules are errors. In a SUBD_CREASES mesh the listed edges,
// and an `ec` record on an edge between two faces, are sharp creases (tspline/sharp_creases: infinitely sharp
// subdivision creases): the model is kept as its mesh; with MULTIPLE_KNOTS they are an error.
//
// Parametrisation: link directions follow from the corners (each face is a counter-clockwise rectangle, turning
// left at every corner), propagated across edges; vertex parameters are sums of knot intervals along links
// from vertex 0, with values that agree to 1e-9 of the domain size merged (interval sums are rounded).
// Star points (extraordinary vertices) and closed strips of faces (a torus, a tube: `has_closed_strip`) leave no
// global (s, t) parametrisation: such a model is kept as its mesh (TsmModel::mesh, evaluated per face by
// TMeshSurface) and TsmModel::spline stays empty.
#include <iosfwd>
#include <map>
#include <string>
#include <string_view>

#include "trivar/tspline/t_mesh.hpp"
#include "trivar/tspline/t_spline.hpp"

namespace trivar::io {

struct TsmReport {
  std::string units;  // e.g. "0.001 millimeters"
  double tolerance = 0;
  int version = 0;
  int deleted = 0;                             // deleted slots (faces, edges, vertices, links)
  int holes = 0;                               // faces without a link (deleted)
  int t_junctions = 0;
  int star_points = 0;
  int crease_edges = 0;                        // sharp creases: `ec` edges between two faces (SUBD_CREASES)
  int repeated_knot_nodes = 0;                 // nodes added by the Bezier end-condition blocks
  std::map<std::string, int> skipped_records;  // record kind -> count (editor state and unknown kinds)
  // The other settings as written, for writing the model back: Rhino gives cap-type 1 and no more; Fusion 360
  // cap-type G1CAPS and the rest (empty or 0 when absent).
  std::string cap_type, star_smoothness;
  std::string end_conditions;  // MULTIPLE_KNOTS or SUBD_CREASES (Fusion); empty: Rhino's force-bezier-end-conditions
  std::string star_knot_rule;  // NURCCS
  double geom_tolerance = 0;
  std::string behavior_version, compat_version;
  bool grip_map = true;        // false: no 0m records, one grip per vertex in vertex order (Fusion)
};

struct TsmModel {
  TSpline spline;  // the global T-spline; empty (no faces) when the mesh has star points, a closed strip or creases
  TMesh mesh;      // the half-edge mesh as read
  TsmReport report;
};

// Throws trivar::Error "name:line: ..." (or "name: ..." for whole-model checks) on a missing header, a
// malformed record, a dangling id, inconsistent links (opp not mutual, a loop that does not close, a link in
// the wrong face), a non-rectangular face, contradictory knot intervals, or grips that do not
// match the grip map.
TsmModel parse_tsm(std::string_view text, const std::string& name);
TsmModel read_tsm(const std::string& path);

// Writes an odd-degree T-spline whose nodes sit on vertices in the same format (vertex frames = the T-image's
// directions; each vertex's nodes become its primary grip, the first node on it, and a grip block at their
// positions along the coincident-neighbour chains), so that read_tsm gives the same surface. Throws
// trivar::Error for even degrees, nodes on links or faces, a vertex whose nodes are not one block, or a domain
// boundary that is not a simple loop at a vertex. Written atomically; nothing is written on error.
void write_tsm(std::ostream& os, const TSpline& ts);
void write_tsm(const std::string& path, const TSpline& ts);
// Writes the half-edge mesh as read (also one with star points): every slot keeps its number (deleted ones as
// bare keywords), so read_tsm gives the same mesh. `settings`: the report of the file it was read from, whose
// settings are written back (Fusion's dialect when it has end-conditions or the mesh subdivision-crease
// boundaries; then without a grip map when the file had none and every live vertex's one grip has its number);
// the default writes Rhino's settings. Written atomically.
void write_tsm(std::ostream& os, const TMesh& mesh, const TsmReport& settings = {});
void write_tsm(const std::string& path, const TMesh& mesh, const TsmReport& settings = {});

}  // namespace trivar::io
