// TSM files as Autodesk Fusion 360 writes them (TSplineBody.saveAsTSMFile): its settings (end-conditions,
// star-knot-rule, the version fields), no grip map (one control point per vertex in vertex order), every vertex
// direction NORTH, and closed cages. The cages are written (fusion_cages.hpp) the way the public descriptions of
// Fusion's output give them (no file exported by Fusion was available): a torus (no star point, periodic both
// ways), a box (eight valence-3 star points) and open grids.
// Files Fusion itself wrote: fusion_readback_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <numbers>
#include <set>
#include <sstream>
#include <tuple>

#include "fusion_cages.hpp"
#include "star_mesh_tsm.hpp"
#include "face_continuity.hpp"
#include "triangulation_loops.hpp"
#include "support/temp_dir.hpp"
#include "tsm_error.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/tsm_format.hpp"
#include "trivar/spline/basis.hpp"
#include "trivar/spline/tensor_spline.hpp"
#include "trivar/tspline/sharp_creases.hpp"
#include "trivar/tspline/t_mesh_surface.hpp"
#include "trivar/tspline/t_mesh_tessellation.hpp"
#include "trivar/tspline/t_spline_surface.hpp"

namespace trivar {
namespace {

using test::fusion_text;
using test::grid_cage;
using test::torus_cage;

// The largest difference (value, d/du, d/dv) at 20 points per face between the surface of a torus cage
// (torus_cage) and its periodic uniform bicubic B-spline, built on the unclamped knots -3 .. n + 3 with the
// control points wrapped.
double deviation_from_periodic_bspline(const TMeshSurface& s, const test::QuadMesh& cage, int nu, int nv) {
  const auto wrapped = [](int n) {
    std::vector<double> k;
    for (int i = -3; i <= n + 3; ++i) k.push_back(i);
    return KnotVector(3, k);
  };
  std::vector<double> coefs;
  for (int j = -1; j <= nv + 1; ++j)
    for (int i = -1; i <= nu + 1; ++i) {
      const auto& p = cage.points[static_cast<std::size_t>(((i % nu + nu) % nu) * nv + (j % nv + nv) % nv)];
      coefs.insert(coefs.end(), p.begin(), p.end());
    }
  const TensorSpline<2> ref({wrapped(nu), wrapped(nv)}, 3, false, coefs);
  double worst = 0;
  for (int f = 0; f < nu * nv; ++f)
    for (double u : {0.0, 0.21, 0.5, 0.83, 1.0})
      for (double v : {0.0, 0.37, 0.64, 1.0}) {
        double a[9], b[9];
        s.eval(f, u, v, a);
        ref.eval_derivs({f / nv + u, f % nv + v}, 1, b);
        for (int d = 0; d < 9; ++d) worst = std::max(worst, std::abs(a[d] - b[d]));
      }
  return worst;
}

std::string with(std::string s, const std::string& from, const std::string& to) {
  const auto i = s.find(from);
  EXPECT_NE(i, std::string::npos) << from;
  return i == std::string::npos ? s : s.replace(i, from.size(), to);
}

TEST(FusionTsm, SettingsAndGripsInVertexOrder) {
  const std::string text = test::fusion_text(test::grid_cage(3, 2), "MULTIPLE_KNOTS", 1.0,
                                       "100edges 0 3\n100verts\n50000grip 0\n50000grip 3\n106ek 1\n");
  // 106ek: one record per edge slot, repeating the intervals; the grid has 17 edges.
  std::string ek;
  for (int e = 0; e < 17; ++e) ek += "106ek 1\n";
  const std::string full = with(text, "106ek 1\n", ek);
  const io::TsmModel m = io::parse_tsm(full, "grid.tsm");
  const io::TsmReport& r = m.report;
  EXPECT_EQ(r.end_conditions, "MULTIPLE_KNOTS");
  EXPECT_EQ(m.mesh.end_conditions, EndConditions::bezier);
  EXPECT_EQ(r.star_knot_rule, "NURCCS");
  EXPECT_EQ(r.cap_type, "G1CAPS");
  EXPECT_EQ(r.units, "1 meters");
  EXPECT_EQ(r.version, 992);
  EXPECT_EQ(r.behavior_version, "14.2.0");
  EXPECT_EQ(r.compat_version, "13.3.0");
  EXPECT_EQ(r.geom_tolerance, 1e-5);
  EXPECT_FALSE(r.grip_map);
  EXPECT_EQ(r.skipped_records, (std::map<std::string, int>{{"50000grip", 2}, {"106ek", 17}}));
  EXPECT_EQ(m.mesh.crease_edges, (std::vector<int>{0, 3}));  // Fusion's crease lists (boundary edges), kept on the mesh
  EXPECT_TRUE(m.mesh.crease_vertices.empty());
  ASSERT_EQ(m.mesh.points.size(), 12u);
  for (int v = 0; v < 12; ++v) EXPECT_EQ(m.mesh.vertices[static_cast<std::size_t>(v)].primary, v);
  EXPECT_FALSE(m.spline.image.faces.empty());  // an open grid: the global T-spline
  EXPECT_EQ(io::parse_tsm(with(full, "MULTIPLE_KNOTS", "SUBD_CREASES"), "g.tsm").mesh.end_conditions, EndConditions::subd_creases);
}

// The torus: no star point, but no global (s, t) either. Every face is the T-spline in a chart of its
// neighbourhood, which with equal intervals is the periodic uniform bicubic B-spline of the cage, built here on
// the unclamped uniform knots -3 .. n + 3 with the control points wrapped.
TEST(FusionTsm, TorusIsThePeriodicBicubicBSpline) {
  const int nu = 16, nv = 10;
  const test::QuadMesh cage = test::torus_cage(nu, nv);
  const std::string text = test::fusion_text(cage);
  const std::clock_t t0 = std::clock();  // CPU time: the test runs on one thread
  const io::TsmModel m = io::parse_tsm(text, "torus.tsm");
  EXPECT_EQ(m.report.star_points, 0);
  EXPECT_TRUE(m.spline.image.faces.empty());
  EXPECT_EQ(m.mesh.end_conditions, EndConditions::subd_creases);
  EXPECT_TRUE(has_closed_strip(m.mesh));
  const TMeshSurface s(m.mesh, 1);
  const double load = double(std::clock() - t0) / CLOCKS_PER_SEC;
  EXPECT_EQ(s.count(FaceMethod::exact), nu * nv);

  const double worst = deviation_from_periodic_bspline(s, cage, nu, nv);
  std::printf("torus %d x %d: read and charted in %.1f ms CPU; max |surface - periodic B-spline| (value, d/du, d/dv) %.2e\n", nu,
              nv, 1e3 * load, worst);
  EXPECT_LT(worst, 1e-12);

  const TSplineTriangulation t = tessellate(s, 1e-2);
  EXPECT_EQ(test::closed_euler_characteristic(t), 0);
  const test::Continuity c = test::continuity(s.mesh(), [&](int f, double u, double v, double* o) { s.eval(f, u, v, o); });
  EXPECT_EQ(c.edges, 2 * nu * nv);
  EXPECT_LT(c.gap, 1e-12);
  EXPECT_LT(c.c1, 1e-12);
}

// Tori whose strips are too short for charts of one ring around a face: 8 faces round carry charts of single
// faces (three rings), fewer only bicubic B-spline cells; both the periodic B-spline. A tube of 7 faces round
// has the boundary within two rings of every face: neither, an error.
TEST(FusionTsm, ShortClosedStrips) {
  for (const auto& [nu, nv, exact] : {std::array<int, 3>{8, 8, 64}, std::array<int, 3>{12, 6, 0}, std::array<int, 3>{4, 3, 0}}) {
    const test::QuadMesh cage = test::torus_cage(nu, nv);
    const TMeshSurface s(io::parse_tsm(test::fusion_text(cage), "t.tsm").mesh, 1);
    EXPECT_EQ(s.count(FaceMethod::exact), exact);
    EXPECT_EQ(s.count(FaceMethod::bicubic), nu * nv - exact);
    const double worst = deviation_from_periodic_bspline(s, cage, nu, nv);
    std::printf("torus %d x %d: max |surface - periodic B-spline| %.2e\n", nu, nv, worst);
    EXPECT_LT(worst, 1e-12);
  }
  test::QuadMesh tube;
  for (int j = 0; j <= 3; ++j)
    for (int i = 0; i < 7; ++i) tube.points.push_back({std::cos(2 * std::numbers::pi * i / 7), std::sin(2 * std::numbers::pi * i / 7), 0.5 * j});
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 7; ++i) tube.quads.push_back({7 * j + i, 7 * j + (i + 1) % 7, 7 * (j + 1) + (i + 1) % 7, 7 * (j + 1) + i});
  const io::TsmModel m = io::parse_tsm(test::fusion_text(tube, "MULTIPLE_KNOTS"), "tube.tsm");
  EXPECT_TRUE(m.spline.image.faces.empty());
  try {
    const TMeshSurface s(m.mesh, 1);
    ADD_FAILURE() << "a tube of 7 faces round was charted";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("closed strip of faces, too short for a chart"), std::string::npos) << msg;
    EXPECT_NE(msg.find("boundary vertex"), std::string::npos) << msg;
  }
}

// The box: a cube of 3 x 3 faces per side, eight valence-3 star points. At every cage vertex the surface is
// the Catmull-Clark limit point (n^2 v + 4 sum e_j + sum f_j) / (n (n + 5)).
TEST(FusionTsm, BoxCageLimitPoints) {
  const test::QuadMesh cage = test::cube_mesh(3);
  const std::clock_t t0 = std::clock();
  const io::TsmModel m = io::parse_tsm(test::fusion_text(cage), "box.tsm");
  EXPECT_EQ(m.report.star_points, 8);
  EXPECT_TRUE(m.spline.image.faces.empty());
  const TMeshSurface s(m.mesh, 1);
  const double load = double(std::clock() - t0) / CLOCKS_PER_SEC;
  std::vector<std::set<int>> edge_nb(cage.points.size()), diagonal(cage.points.size());
  for (const auto& q : cage.quads)
    for (int k = 0; k < 4; ++k) {
      edge_nb[q[k]].insert({q[(k + 1) % 4], q[(k + 3) % 4]});
      diagonal[q[k]].insert(q[(k + 2) % 4]);
    }
  const std::array<std::array<double, 2>, 4> at{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
  double worst = 0;
  int checked = 0;
  for (int f = 0; f < s.num_faces(); ++f) {
    const auto corners = s.corners(f);
    for (int k = 0; k < 4; ++k) {
      const int v = corners[static_cast<std::size_t>(k)];
      const double n = static_cast<double>(edge_nb[v].size());
      std::array<double, 3> limit{};
      for (int c = 0; c < 3; ++c) {
        double e = 0, d = 0;
        for (int x : edge_nb[v]) e += cage.points[x][c];
        for (int x : diagonal[v]) d += cage.points[x][c];
        limit[c] = (n * n * cage.points[v][c] + 4 * e + d) / (n * (n + 5));
      }
      double o[9];
      s.eval(f, at[static_cast<std::size_t>(k)][0], at[static_cast<std::size_t>(k)][1], o);
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(o[c] - limit[static_cast<std::size_t>(c)]));
      ++checked;
    }
  }
  EXPECT_EQ(checked, 4 * 54);
  std::printf("box 3 x 3 x 6: read and set up in %.1f ms CPU; max |surface - Catmull-Clark limit point| %.2e\n", 1e3 * load, worst);
  EXPECT_LT(worst, 1e-12);
  const test::Continuity c = test::continuity(s.mesh(), [&](int f, double u, double v, double* o) { s.eval(f, u, v, o); });
  EXPECT_EQ(c.edges, 108);
  EXPECT_LT(c.gap, 1e-14);
  EXPECT_LT(c.normal_angle, 1e-12);
  EXPECT_EQ(test::closed_euler_characteristic(tessellate(s, 1e-3)), 2);
}

// An open grid with Bezier end conditions (MULTIPLE_KNOTS) and no end-condition blocks: each vertex's blending
// function is the B-spline of its local knots, repeated at the boundary, so the surface is the bicubic on the
// clamped knots 0, 0, 0, 0, 1, ..., n, n, n, n without its first and last function per direction, evaluated as
// sum P B / sum B. A single quad is then the bilinear patch of its corners (the clamped bicubic of its
// degree-elevated net).
TEST(FusionTsm, OpenGridWithMultipleKnotsIsTheClampedBicubic) {
  // Without a grip map the boundary's repeated-knot nodes sit on the boundary vertices: the clamped bicubic of the
  // cage with its boundary rows doubled, a partition of unity up to the boundary (evaluated there too).
  for (const auto& [nx, ny] : {std::array<int, 2>{1, 1}, std::array<int, 2>{3, 2}}) {
    const test::QuadMesh cage = test::grid_cage(nx, ny);
    const io::TsmModel m = io::parse_tsm(test::fusion_text(cage, "MULTIPLE_KNOTS", 0.5), "grid.tsm");
    const TSplineSurface surf(m.spline);
    const auto clamped = [](int n) {
      std::vector<double> k{0, 0, 0};
      for (int i = 0; i <= n; ++i) k.push_back(0.5 * i);
      k.insert(k.end(), {0.5 * n, 0.5 * n, 0.5 * n});
      return KnotVector(3, k);
    };
    const KnotVector ks = clamped(nx), kt = clamped(ny);
    double worst = 0;
    for (double s : {0.0, 0.01, 0.2, 0.45, 0.7, 0.99, 1.0})
      for (double t : {0.0, 0.02, 0.3, 0.5, 0.98, 1.0}) {
        const double x = s * 0.5 * nx, y = t * 0.5 * ny;
        double ns[4], nt[4];
        const int ss = ks.find_span(x), st = kt.find_span(y);
        basis_values(ks, ss, x, ns);
        basis_values(kt, st, y, nt);
        std::array<double, 3> num{};
        double den = 0;
        for (int b = 0; b < 4; ++b)
          for (int a = 0; a < 4; ++a) {
            // Function k of the clamped basis is vertex k - 1's; the first and last are the boundary vertices'
            // repeated-knot nodes, placed on them.
            const int i = std::clamp(ss - 3 + a - 1, 0, nx), j = std::clamp(st - 3 + b - 1, 0, ny);
            const double w = ns[a] * nt[b];
            den += w;
            for (int c = 0; c < 3; ++c) num[static_cast<std::size_t>(c)] += w * cage.points[static_cast<std::size_t>(j * (nx + 1) + i)][static_cast<std::size_t>(c)];
          }
        double o[3];
        surf.eval({x, y}, o);
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(o[c] - num[static_cast<std::size_t>(c)] / den));
        // One face: the cubic Bezier of the rows P0, P0, P1, P1 in each direction, the bilinear patch of the
        // corners at (h(s), h(t)) with h = 3 s^2 - 2 s^3.
        if (nx == 1 && ny == 1)
          for (int c = 0; c < 3; ++c) {
            const auto P = [&](int i) { return cage.points[static_cast<std::size_t>(i)][static_cast<std::size_t>(c)]; };
            const double hs = s * s * (3 - 2 * s), ht = t * t * (3 - 2 * t);
            EXPECT_NEAR(o[c], (1 - hs) * (1 - ht) * P(0) + hs * (1 - ht) * P(1) + hs * ht * P(3) + (1 - hs) * ht * P(2), 1e-13);
          }
      }
    EXPECT_LT(worst, 1e-13) << nx << " x " << ny;
  }
}

TEST(FusionTsm, MalformedFilesGiveOneLineErrors) {
  const std::string box = test::fusion_text(test::cube_mesh(2));
  test::expect_tsm_error(with(box, "end-conditions SUBD_CREASES", "end-conditions PERIODIC"), "end-conditions PERIODIC is not read");
  test::expect_tsm_error(with(box, "star-knot-rule NURCCS", "star-knot-rule CATMULL_CLARK"), "star-knot-rule CATMULL_CLARK is not read");
  // One control point too many, one deleted.
  test::expect_tsm_error(with(box, "\ntol ", "0g 1 2 3 1\n\ntol "), "27 control points (0g) for 26 vertices");
  test::expect_tsm_error(with(box, "0g 1 1 1 1\n", "0g\n"), "is deleted");
  // Dangling ids.
  test::expect_tsm_error(with(box, "l 3 1 ", "l 3 99 "), "names a link that does not exist");
  test::expect_tsm_error(with(box, "f 4 0", "f 400 0"), "names link 400, which does not exist");
  test::expect_tsm_error(with(box, "\nv 0 NORTH", "\nv 0 UP"), "needs an outgoing link and a direction");
  // A crease between two faces: with MULTIPLE_KNOTS an error; with SUBD_CREASES one crease edge alone (the cube has
  // no boundary) ends inside the mesh at both ends, two darts (dart_test.cpp). On the boundary of a grid, ec
  // records are read.
  test::expect_tsm_error(with(with(box, "\ntol ", "ec 3 0\n\ntol "), "SUBD_CREASES", "MULTIPLE_KNOTS"),
                         "edge 3 between two faces is a crease (ec); creases inside the mesh are read with end-conditions SUBD_CREASES, not MULTIPLE_KNOTS");
  const auto ends = [](const std::string& text) { return crease_singularities(TMeshSurface(io::parse_tsm(text, "c.tsm").mesh, 1).mesh()); };
  EXPECT_EQ(ends(with(box, "\ntol ", "ec 3 0\n\ntol ")).darts.size(), 2u);
  // The same from Fusion's crease list.
  test::expect_tsm_error(with(with(box, "\ntol ", "100edges 3\n100verts\n\ntol "), "SUBD_CREASES", "MULTIPLE_KNOTS"),
                         "crease edge 3 lies between two faces; creases inside the mesh are read with end-conditions SUBD_CREASES, not MULTIPLE_KNOTS");
  EXPECT_EQ(ends(with(box, "\ntol ", "100edges 3\n100verts\n\ntol ")).darts.size(), 2u);
  // Creased vertices: with MULTIPLE_KNOTS an error; inside the mesh on no crease a cone point.
  test::expect_tsm_error(with(with(box, "\ntol ", "100edges\n100verts 5\n\ntol "), "SUBD_CREASES", "MULTIPLE_KNOTS"),
                         "creased vertex 5: creased vertices are read with end-conditions SUBD_CREASES, not MULTIPLE_KNOTS");
  EXPECT_EQ(ends(with(box, "\ntol ", "100edges\n100verts 5\n\ntol ")).cone_points, std::vector<int>{5});
  EXPECT_EQ(io::parse_tsm(with(fusion_text(grid_cage(1, 1)), "\ntol ", "ec 0 0\n\ntol "), "g.tsm").mesh.conditions.size(), 1u);
  // Edge knots other than the intervals.
  std::string ek;
  for (int e = 0; e < 48; ++e) ek += e == 5 ? "106ek 0\n" : "106ek 1\n";
  test::expect_tsm_error(with(box, "\ntol ", ek + "\ntol "), "edge knot (106ek) 0 of edge 5 is not its knot interval 1");
  test::expect_tsm_error(with(box, "\ntol ", "106ek 1\n\ntol "), "1 edge knot records (106ek) for 48 edges");
}

// Written back in Fusion's dialect (no grip map, its settings) and read again: the same mesh, settings and
// surface, bit for bit.
TEST(FusionTsm, ReadWriteReadRoundTrip) {
  for (const std::string& text : {test::fusion_text(test::torus_cage(12, 10)), test::fusion_text(test::cube_mesh(3)),
                                  test::fusion_text(test::grid_cage(3, 2), "MULTIPLE_KNOTS", 0.5)}) {
    const io::TsmModel a = io::parse_tsm(text, "a.tsm");
    std::ostringstream os;
    io::write_tsm(os, a.mesh, a.report);
    const std::string written = os.str();
    EXPECT_EQ(written.find("0m "), std::string::npos);
    EXPECT_NE(written.find("\nend-conditions " + a.report.end_conditions + "\nstar-knot-rule NURCCS\n"), std::string::npos);
    EXPECT_NE(written.find("\nbehavior-version 14.2.0\ncompat-version 13.3.0\n"), std::string::npos);
    const io::TsmModel b = io::parse_tsm(written, "b.tsm");
    EXPECT_EQ(b.report.end_conditions, a.report.end_conditions);
    EXPECT_EQ(b.report.cap_type, "G1CAPS");
    EXPECT_EQ(b.report.units, a.report.units);
    EXPECT_EQ(b.report.version, 992);
    EXPECT_EQ(b.report.geom_tolerance, a.report.geom_tolerance);
    EXPECT_FALSE(b.report.grip_map);
    EXPECT_EQ(b.mesh.end_conditions, a.mesh.end_conditions);
    ASSERT_EQ(b.mesh.links.size(), a.mesh.links.size());
    for (std::size_t l = 0; l < a.mesh.links.size(); ++l) {
      const TMeshLink &x = a.mesh.links[l], &y = b.mesh.links[l];
      EXPECT_EQ(std::tie(x.prev, x.next, x.opp, x.vertex, x.face, x.edge, x.flag, x.frame),
                std::tie(y.prev, y.next, y.opp, y.vertex, y.face, y.edge, y.flag, y.frame));
    }
    EXPECT_EQ(b.mesh.intervals, a.mesh.intervals);
    ASSERT_EQ(b.mesh.points.size(), a.mesh.points.size());
    for (std::size_t g = 0; g < a.mesh.points.size(); ++g) EXPECT_EQ(b.mesh.points[g].xyz, a.mesh.points[g].xyz);
    const TMeshSurface sa(a.mesh, 1), sb(b.mesh, 1);
    for (int f = 0; f < sa.num_faces(); ++f) {
      double x[9], y[9];
      sa.eval(f, 0.3, 0.8, x);
      sb.eval(f, 0.3, 0.8, y);
      for (int d = 0; d < 9; ++d) EXPECT_EQ(x[d], y[d]);
    }
  }
}

// The command line: info names the Fusion settings, eval takes FACE U V, convert writes closed triangle meshes
// and STEP patches.
TEST(FusionTsm, CommandLine) {
  const test::TempDir dir;
  const std::string torus = dir.file("torus.tsm"), box = dir.file("box.tsm");
  std::ofstream(torus) << fusion_text(torus_cage(16, 10));
  std::ofstream(box) << fusion_text(test::cube_mesh(3), "MULTIPLE_KNOTS");
  const auto run = [&](const std::string& args) { return test::run_cli(dir, args); };
  const std::string info = run("info " + torus);
  EXPECT_NE(info.find("closed strip of faces"), std::string::npos) << info;
  EXPECT_NE(info.find("Fusion 360: end conditions SUBD_CREASES, star knot rule NURCCS, cap type G1CAPS, version 992, "
                      "behavior version 14.2.0, compat version 13.3.0; no grip map"),
            std::string::npos)
      << info;
  EXPECT_NE(run("eval " + torus + " 17 0.5 0.5").find("face 17: exact"), std::string::npos);
  for (const std::string& file : {torus, box}) {
    run("convert " + file + " " + dir.file("t.obj"));
    // The OBJ's vertices and faces: closed, of the cage's Euler characteristic.
    EXPECT_EQ(test::closed_euler_characteristic(test::obj_triangles(dir.file("t.obj"))), file == torus ? 0 : 2);
  }
  EXPECT_NE(run("convert " + box + " " + dir.file("t.stp")).find("Bezier patches"), std::string::npos);
  run("convert " + box + " " + dir.file("t.tsm"));
  EXPECT_EQ(io::read_tsm(dir.file("t.tsm")).report.end_conditions, "MULTIPLE_KNOTS");
}

}  // namespace
}  // namespace trivar
