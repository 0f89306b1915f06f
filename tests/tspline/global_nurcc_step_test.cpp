// Global non-uniform Catmull-Clark steps (non_uniform_subdivision): the surface after forced steps against the
// surface without them (uniform Catmull-Clark by Stam's method, the T-spline in charts, NonUniformStar on the
// star points' own sectors), against OpenSubdiv's uniform Catmull-Clark limit surface, and a cage whose star
// points are too close for NonUniformStar without the steps. Local non-uniform subdivision (crease faces of a
// mesh without creases), which takes such star points where the steps do not apply: against the steps' surface,
// against OpenSubdiv with equal intervals, and on open boxes (Bezier rims) for continuity and the star points' limits.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "crease_nets.hpp"
#include "face_continuity.hpp"
#include "fusion_cages.hpp"
#include "osd_reference.hpp"
#include "patch_check.hpp"
#include "star_mesh_tsm.hpp"
#include "support/temp_dir.hpp"
#include "triangulation_loops.hpp"
#include "tsm_error.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/tsm_format.hpp"
#include "trivar/tspline/non_uniform_subdivision.hpp"
#include "trivar/tspline/t_mesh_surface.hpp"
#include "trivar/tspline/t_mesh_tessellation.hpp"

namespace trivar {
namespace {

// A box cage (box_mesh) with its points moved off the box (no symmetry hides a wrong frame) and knot interval
// `wide` on the strip of faces round it between x grid lines `strip` and strip + 1.
std::string stepped_box_text(const std::array<int, 3>& n, bool open_bottom, int strip, double wide) {
  test::QuadMesh q = test::box_mesh(n, open_bottom);
  const test::QuadMesh grid = q;  // the grid positions, before the points move
  for (auto& p : q.points) {
    const auto r = p;
    p = {r[0] + 0.05 * std::sin(2.1 * r[1] + 0.4 * r[2]), r[1] + 0.04 * std::cos(1.7 * r[2] - 0.3 * r[0]),
         r[2] + 0.06 * std::sin(1.3 * r[0] + 0.9 * r[1])};
  }
  const auto gx = [&](int v) { return static_cast<int>(std::lround((grid.points[static_cast<std::size_t>(v)][0] + 1) * n[0] / 2)); };
  for (const auto& f : q.quads)
    for (int k = 0; k < 4; ++k) {
      const int a = f[static_cast<std::size_t>(k)], b = f[static_cast<std::size_t>((k + 1) % 4)];
      if (std::min(gx(a), gx(b)) == strip && std::max(gx(a), gx(b)) == strip + 1) q.intervals[{a, b}] = wide;
    }
  return test::tsm_text(q);
}
TMesh stepped_box(const std::array<int, 3>& n, bool open_bottom, int strip, double wide) {
  return io::parse_tsm(stepped_box_text(n, open_bottom, strip, wide), "stepped_box.tsm").mesh;
}

// The cube cage of n x n faces per side.
TMesh stepped_box(int n, int strip, double wide) { return stepped_box({n, n, n}, false, strip, wide); }

// Sample points of a face: a 4 x 4 grid with its corners, and points 2^-7 .. 1e-3 from each corner.
std::vector<std::array<double, 2>> stepped_samples() {
  std::vector<std::array<double, 2>> uv;
  for (double u : {0.0, 0.3, 0.65, 1.0})
    for (double v : {0.0, 0.4, 0.75, 1.0}) uv.push_back({u, v});
  for (double a : {0.0, 1.0})
    for (double b : {0.0, 1.0})
      for (const auto& n : {std::array<double, 2>{1.0 / 128, 1.0 / 256}, {1e-3, 0.5e-3}, {0.3, 1e-3}}) uv.push_back({a == 0 ? n[0] : 1 - n[0], b == 0 ? n[1] : 1 - n[1]});
  return uv;
}

struct StepDeviation {
  double position = 0, derivative = 0;  // relative to the derivatives' size
};

// Surface `a` (the mesh as given) against `b` (after global steps, evaluated on the faces as given).
StepDeviation step_deviation(const TMeshSurface& a, const TMeshSurface& b, const std::vector<int>& faces) {
  StepDeviation d;
  for (int f : faces)
    for (const auto& [u, v] : stepped_samples()) {
      double x[9], y[9];
      a.eval(f, u, v, x);
      b.eval_source(f, u, v, y);
      d.position = std::max(d.position, std::hypot(x[0] - y[0], x[1] - y[1], x[2] - y[2]));
      if ((u == 0 || u == 1) && (v == 0 || v == 1)) continue;  // at a star corner the derivatives are directions
      const double size = std::max({std::hypot(x[3], x[4], x[5]), std::hypot(x[6], x[7], x[8]), 1e-300});
      for (int k = 3; k < 9; ++k) d.derivative = std::max(d.derivative, std::abs(x[k] - y[k]) / size);
    }
  return d;
}

std::vector<int> all_faces(const TMeshSurface& s) {
  std::vector<int> f(static_cast<std::size_t>(s.num_faces()));
  for (int i = 0; i < s.num_faces(); ++i) f[static_cast<std::size_t>(i)] = i;
  return f;
}

// Equal intervals: the steps are uniform Catmull-Clark steps, the surface (Stam's patches, one local step at the
// faces with several star corners) does not change, and it is OpenSubdiv's.
TEST(GlobalNurccStep, EqualIntervalsLeaveTheSurfaceUnchanged) {
  const TMesh mesh = stepped_box(3, 1, 1.0);
  const TMeshSurface s(mesh, 1);
  EXPECT_EQ(s.global_steps(), 0);  // close star points, equal intervals: no steps needed
  EXPECT_EQ(s.count(FaceMethod::star), 24);
  const TMeshSurface s1(mesh, 1, 1), s2(mesh, 1, 2);
  ASSERT_EQ(s1.num_faces(), 4 * 54);
  ASSERT_EQ(s2.num_faces(), 16 * 54);
  EXPECT_EQ(s2.source_face(16 * 7 + 5), 7);
  EXPECT_EQ(s2.source_mesh().faces.size(), 54u);
  const StepDeviation d1 = step_deviation(s, s1, all_faces(s)), d2 = step_deviation(s, s2, all_faces(s));
  EXPECT_LT(d1.position, 1e-13);
  EXPECT_LT(d1.derivative, 1e-11);
  EXPECT_LT(d2.position, 1e-13);
  EXPECT_LT(d2.derivative, 1e-11);
  // OpenSubdiv on the mesh as given (its face frames are trivar's: corners from the first corner link).
  test::PolyMesh p;
  for (const TMeshVertex& v : mesh.vertices) p.points.push_back(mesh.points[static_cast<std::size_t>(v.primary)].xyz);
  for (int f = 0; f < s.num_faces(); ++f) {
    const auto c = s.corners(f);
    p.faces.push_back({c.begin(), c.end()});
  }
  const test::OsdLimitSurface osd(p);
  double osd_position = 0, osd_derivative = 0;
  for (int f = 0; f < s.num_faces(); ++f)
    for (const auto& [u, v] : stepped_samples()) {
      double y[9];
      s2.eval_source(f, u, v, y);
      const test::LimitSample o = osd.eval(f, u, v);
      osd_position = std::max(osd_position, std::hypot(y[0] - o.p[0], y[1] - o.p[1], y[2] - o.p[2]));
      const bool corner = (u == 0 || u == 1) && (v == 0 || v == 1);  // the star corners' parametrisation is singular
      if (!corner)
        osd_derivative = std::max({osd_derivative, std::hypot(y[3] - o.du[0], y[4] - o.du[1], y[5] - o.du[2]),
                                   std::hypot(y[6] - o.dv[0], y[7] - o.dv[1], y[8] - o.dv[2])});
    }
  EXPECT_LT(osd_position, 1e-12);
  EXPECT_LT(osd_derivative, 1e-10);
  std::printf("box 3 x 3, equal intervals: 1 step %.1e / %.1e, 2 steps %.1e / %.1e (position / relative derivatives); "
              "2 steps against OpenSubdiv %.1e / %.1e\n", d1.position, d1.derivative, d2.position, d2.derivative, osd_position, osd_derivative);
}

// Unequal intervals, star points 7 edges apart: NonUniformStar evaluates the mesh as given, and the forced step
// must give the same surface on every face (the step's rules are NonUniformStar's first level at the star
// points and exact knot insertion elsewhere, where the faces are the T-spline in charts of the mesh as given).
TEST(GlobalNurccStep, UnequalIntervalsFarApartMatchNonUniformStar) {
  // The strip 3 edges from every star point (after the step 6, beyond the three rings: uniform Stam patches there
  // and bicubic cells on the unequal knots), or 1 from four of them and 5 from the others (after the step 2, still
  // non-uniform, and 10). The faces' sides are compared too: where the intervals jump, each face's derivatives
  // are its own (one-sided).
  for (const auto& [strip, wide, nurcc_stars, stepped_nurcc] : {std::tuple{3, 1.02, 8, 0}, std::tuple{1, 1.5, 4, 4}}) {
    const TMesh mesh = stepped_box(7, strip, wide);
    const TMeshSurface s(mesh, 1);
    EXPECT_EQ(s.global_steps(), 0);
    EXPECT_EQ(s.non_uniform_stars(), nurcc_stars);
    const TMeshSurface s1(mesh, 1, 1);
    EXPECT_EQ(s1.non_uniform_stars(), stepped_nurcc);
    std::vector<int> nurcc, other;
    for (int f = 0; f < s.num_faces(); ++f) (s.method(f) == FaceMethod::non_uniform ? nurcc : other).push_back(f);
    const StepDeviation dn = step_deviation(s, s1, nurcc), dx = step_deviation(s, s1, other);
    EXPECT_LT(dn.position, 1e-13);
    EXPECT_LT(dn.derivative, 1e-11);
    EXPECT_LT(dx.position, 1e-13);
    EXPECT_LT(dx.derivative, 1e-11);
    std::printf("box 7 x 7, strip %d at %.2f: one forced step against the mesh as given: %zu non-uniform faces %.1e / %.1e, %zu "
                "others (exact %d, bicubic %d) %.1e / %.1e\n", strip, wide, nurcc.size(), dn.position, dn.derivative, other.size(),
                s.count(FaceMethod::exact), s.count(FaceMethod::bicubic), dx.position, dx.derivative);
  }
}

// Star points 3 edges apart with a strip of unequal intervals: two steps (3 -> 12 edges), then NonUniformStar.
TEST(GlobalNurccStep, CloseStarPointsWithUnequalIntervalsAreStepped) {
  const TMesh mesh = stepped_box(3, 1, 1.5);
  EXPECT_EQ(nurcc_steps_needed(mesh, TMeshSurface::kStarsApart), 2);
  const TMeshSurface s(mesh, 1);
  EXPECT_EQ(s.global_steps(), 2);
  EXPECT_EQ(s.non_uniform_stars(), 0);  // after the steps the strip is beyond the star points' three rings
  const test::Continuity c = test::continuity(s.mesh(), [&](int f, double u, double v, double* o) { s.eval(f, u, v, o); });
  EXPECT_EQ(c.edges, 16 * 108);
  EXPECT_LT(c.gap, 1e-12);
  EXPECT_LT(c.normal_angle, 1e-9);
  EXPECT_LT(c.c1, 0.5 + 1e-9);  // C1 in the knots: across the strip's sides the derivatives differ by the ratio 1.5
  // Three steps: the same surface.
  const TMeshSurface s3(mesh, 1, 3);
  double gap = 0;
  for (int f = 0; f < static_cast<int>(mesh.faces.size()); ++f)
    for (const auto& [u, v] : stepped_samples()) {
      double x[9], y[9];
      s.eval_source(f, u, v, x);
      s3.eval_source(f, u, v, y);
      gap = std::max(gap, std::hypot(x[0] - y[0], x[1] - y[1], x[2] - y[2]));
    }
  EXPECT_LT(gap, 1e-13);
  const TSplineTriangulation t = tessellate(s, 1e-3);
  EXPECT_EQ(test::closed_euler_characteristic(t), 2);
  std::printf("box 3 x 3, strip at 1.5: 2 steps, %d faces (non-uniform %d, bicubic %d, exact %d); continuity gap %.1e, "
              "normals %.1e, C1 %.1e; 3 steps against 2: %.1e\n", s.num_faces(), s.count(FaceMethod::non_uniform),
              s.count(FaceMethod::bicubic), s.count(FaceMethod::exact), c.gap, c.normal_angle, c.c1, gap);
}

// Without steps (forced to none) the faces near the close star points are crease faces: local subdivision of each
// face's two rings with the same NURCC rules. The surface must be the one after the steps on every face.
TEST(GlobalNurccStep, LocalSubdivisionIsTheSurfaceAfterTheSteps) {
  const TMesh mesh = stepped_box(3, 1, 1.5);
  const TMeshSurface local(mesh, 1, 0), stepped(mesh, 1);
  ASSERT_EQ(stepped.global_steps(), 2);
  ASSERT_EQ(local.num_faces(), 54);
  EXPECT_GT(local.count(FaceMethod::crease), 24);
  const StepDeviation d = step_deviation(local, stepped, all_faces(local));
  EXPECT_LT(d.position, 1e-13);
  EXPECT_LT(d.derivative, 1e-11);  // 2^-10 from the star corners (sub-faces of level 10: rounding times 2^10)
  std::printf("box 3 x 3, strip at 1.5, no steps: %d crease faces (local subdivision), %d star, %d subdivided; against 2 global "
              "steps %.1e / %.1e (position / relative derivatives)\n", local.count(FaceMethod::crease), local.count(FaceMethod::star),
              local.count(FaceMethod::subdivided), d.position, d.derivative);
}

// The Bezier patches of meshes with a strip at 1.5 whose faces near the star points are crease faces: the 3 x 3
// box forced to local subdivision and the open 3 x 3 x 7 box with its Bezier rim. The crease faces' B-spline
// cells are exact patches (the surface to rounding at 5 x 5 points each), the corner patches within the
// tolerance; the pieces tile each face and meet C0.
TEST(GlobalNurccStep, PatchesOfLocalSubdivision) {
  for (const bool open : {false, true}) {
    const TMesh mesh = open ? stepped_box({3, 3, 7}, true, 2, 1.5) : stepped_box(3, 1, 1.5);
    const TMeshSurface s(mesh, 1, open ? -1 : 0);  // the closed box without its global steps
    ASSERT_GT(s.count(FaceMethod::crease), 0);
    const TMeshPatches p = t_mesh_patches(s);
    const test::PatchCheck c = test::expect_patches_hold(s, p, open ? "open" : "closed");
    std::printf("%s, strip at 1.5: %zu patches (%d corner), %d levels; exact patches off the surface by %.1e, corner patches "
                "by %.2e (tolerance %.2e); areas off 1 by %.1e; gaps: exact pieces %.1e, at corner patches %.1e, across edges "
                "%.1e\n",
                open ? "open box 3 x 3 x 7" : "box 3 x 3, no steps", p.patches.size(), p.corner_patches, p.levels, c.exact,
                c.constructed, p.tolerance, c.area, c.inner_gap, c.corner_gap, c.edge_gap);
  }
}

// The largest spread, over the star points, of the limit positions and normals that the faces round each star
// point give at it.
struct StarSpread {
  double position = 0, normal = 0;
};
StarSpread star_spread(const TMeshSurface& s) {
  StarSpread r;
  for (int star : s.stars()) {
    std::vector<std::array<double, 9>> at;
    for (int f = 0; f < s.num_faces(); ++f) {
      const auto c = s.corners(f);
      const auto k = std::find(c.begin(), c.end(), star) - c.begin();
      if (k == 4) continue;
      std::array<double, 9> o{};
      s.eval(f, k == 1 || k == 2 ? 1 : 0, k >= 2 ? 1 : 0, o.data());
      at.push_back(o);
    }
    for (const auto& a : at)
      for (const auto& b : at) {
        const auto na = test::unit_normal(a.data()), nb = test::unit_normal(b.data());
        r.position = std::max(r.position, std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]));
        r.normal = std::max(r.normal, std::hypot(na[0] - nb[0], na[1] - nb[1], na[2] - nb[2]));
      }
  }
  return r;
}

// Open boxes whose rim (the bottom) is a Bezier boundary, which the global steps do not take, with a strip at 1.5
// over the top and down two sides: the top's star points 3 edges apart (a 3 x 3 top), or joined by edges (a 3 x 1
// 5 x 1
// top, whose end faces have two star corners; a narrower box has closed rows of faces too short for charts). Refused before; their faces near the star points are crease faces
// now, the others exact (the T-spline) as before. Continuity across every edge (derivatives per knot unit), one
// limit point and tangent plane at each star point.
TEST(GlobalNurccStep, OpenBoxesWithCloseStarPointsAndUnequalIntervals) {
  for (const auto& [w, n] : {std::array<int, 2>{3, 3}, {5, 1}}) {
    const TMesh mesh = stepped_box({w, n, 7}, true, 2, 1.5);
    EXPECT_EQ(nurcc_steps_needed(mesh, TMeshSurface::kStarsApart), 0);
    const TMeshSurface s(mesh, 1);
    ASSERT_EQ(s.stars().size(), 4u);
    EXPECT_GT(s.count(FaceMethod::crease), 0);
    EXPECT_GT(s.count(FaceMethod::exact), 0);
    const test::Continuity c = test::continuity(s.mesh(), test::knot_units(s));
    EXPECT_EQ(c.edges, 2 * (w * n + 2 * (w + n) * 7) - (w + n));  // every edge but the rim's
    EXPECT_LT(c.gap, 1e-12);
    EXPECT_LT(c.normal_angle, 1e-10);
    EXPECT_LT(c.c1, 1e-10);
    const StarSpread st = star_spread(s);
    EXPECT_LT(st.position, 1e-13);
    EXPECT_LT(st.normal, 1e-10);
      std::printf("open box %d x %d x 7, strip at 1.5: %d crease faces, %d exact, %d star, %d bicubic; across %d edges gap %.1e, "
                "normals %.1e, C1 %.1e (knot units); at the star points positions %.1e, normals %.1e\n", w, n,
                s.count(FaceMethod::crease), s.count(FaceMethod::exact), s.count(FaceMethod::star), s.count(FaceMethod::bicubic),
                c.edges, c.gap, c.normal_angle, c.c1, st.position, st.normal);
  }
  // The command line counts them as local subdivision near star points.
  const test::TempDir dir;
  const std::string path = dir.file("open_box.tsm");
  std::ofstream(path) << stepped_box_text({3, 3, 7}, true, 2, 1.5);
  const TMeshSurface s(io::read_tsm(path).mesh, 1);
  const std::string info = test::run_cli(dir, "info " + path);
  EXPECT_NE(info.find(std::to_string(s.count(FaceMethod::crease)) + " faces near star points with unequal knot intervals"), std::string::npos) << info;
}

// A valence-5 fan (11 x 11 faces per sector) whose sector 0 loses its quadrant beyond (3, 3), the quadrant's two
// sides glued: a valence-3 star point there, on the third ring of the valence-5 one and it on its, both with
// their own three regular rings (NonUniformStar's sectors) and unequal intervals (the strips within 3 of the fan's
// centre). Face [1, 2]^2 of sector 0 lies in the cells of both: refused before, now by local subdivision, the
// other faces of their cells NonUniformStar's. Continuity across every edge, one limit point at each star point.
TEST(GlobalNurccStep, FaceInTheCellsOfTwoStarPoints) {
  constexpr int m = 11;
  const auto height = [](double x, double y) { return 0.2 * std::sin(0.5 * x + 0.3 * y) + 0.02 * x * y; };
  test::QuadMesh fan = test::fan_mesh_with_intervals(5, m, height, [](int k, int i) { return i < 3 ? 1 + 0.25 * ((k + i) % 3) : 1.0; });
  const auto quad = [&](int i, int j) { return fan.quads[static_cast<std::size_t>(j * m + i)]; };  // sector 0
  const auto id = [&](int i, int j) {
    return i < m && j < m ? quad(i, j)[0] : i == m && j < m ? quad(m - 1, j)[1] : i < m ? quad(i, m - 1)[3] : quad(m - 1, m - 1)[2];
  };
  std::map<int, int> glued;  // (3, 3 + t) -> (3 + t, 3)
  for (int t = 1; t <= m - 3; ++t) glued[id(3, 3 + t)] = id(3 + t, 3);
  test::QuadMesh q;
  std::map<int, int> renumber;
  const auto keep = [&](int v) {
    if (glued.count(v)) v = glued.at(v);
    auto [it, fresh] = renumber.emplace(v, static_cast<int>(q.points.size()));
    if (fresh) q.points.push_back(fan.points[static_cast<std::size_t>(v)]);
    return it->second;
  };
  for (std::size_t f = 0; f < fan.quads.size(); ++f) {
    if (f < static_cast<std::size_t>(m * m) && static_cast<int>(f) % m >= 3 && static_cast<int>(f) / m >= 3) continue;
    std::array<int, 4> g{};
    for (std::size_t k = 0; k < 4; ++k) g[k] = keep(fan.quads[f][k]);
    q.quads.push_back(g);
  }
  const auto kept = [&](int v) { return renumber.at(glued.count(v) ? glued.at(v) : v); };
  for (const auto& [ends, d] : fan.intervals)  // the glued sides' two entries agree (interval 1 beyond 3)
    if (renumber.count(glued.count(ends[0]) ? glued.at(ends[0]) : ends[0]) && renumber.count(glued.count(ends[1]) ? glued.at(ends[1]) : ends[1]))
      q.intervals[{kept(ends[0]), kept(ends[1])}] = d;
  const TMesh mesh = io::parse_tsm(test::tsm_text(q), "two_stars.tsm").mesh;
  const TMeshSurface s(mesh, 1);
  ASSERT_EQ(s.stars().size(), 2u);
  EXPECT_EQ(s.non_uniform_stars(), 2);
  EXPECT_EQ(s.count(FaceMethod::crease), 1);
  EXPECT_EQ(s.count(FaceMethod::non_uniform), 4 * 5 + 4 * 3 - 2);
  const test::Continuity c = test::continuity(s.mesh(), test::knot_units(s));
  EXPECT_LT(c.gap, 1e-12);
  EXPECT_LT(c.normal_angle, 1e-9);
  EXPECT_LT(c.c1, 1e-9);
  const StarSpread st = star_spread(s);
  EXPECT_LT(st.position, 1e-13);
  std::printf("valence-5 and valence-3 star points on each other's third ring, unequal intervals: %d crease face, %d non-uniform, "
              "%d star, %d bicubic, %d exact; across %d edges gap %.1e, normals %.1e, C1 %.1e (knot units); at the star points "
              "positions %.1e, normals %.1e\n", s.count(FaceMethod::crease), s.count(FaceMethod::non_uniform), s.count(FaceMethod::star),
              s.count(FaceMethod::bicubic), s.count(FaceMethod::exact), c.edges, c.gap, c.normal_angle, c.c1, st.position, st.normal);
}

// Equal intervals: the open box of a 5 x 1 top is evaluated through one uniform step next to its star points
// joined by edges (subdivided faces); local subdivision of the same faces' nets (written by the test) must be
// OpenSubdiv's limit surface as well.
TEST(GlobalNurccStep, LocalSubdivisionOfSeveralStarCornersIsOpenSubdivs) {
  test::QuadMesh q = test::box_mesh({5, 1, 7}, true);
  for (auto& p : q.points) p[2] += 0.1 * std::sin(1.3 * p[0] + 0.7 * p[1]);
  const TMesh mesh = io::parse_tsm(test::tsm_text(q), "open_box.tsm").mesh;
  const TMeshSurface s(mesh, 1);
  test::PolyMesh p;
  p.points = q.points;
  for (const auto& f : q.quads) p.faces.push_back({f.begin(), f.end()});
  const test::OsdLimitSurface osd(p);
  double to_osd = 0, to_surface = 0;
  int faces = 0;
  for (int f = 0; f < s.num_faces(); ++f) {
    if (s.method(f) != FaceMethod::subdivided) continue;
    ++faces;
    const CreaseFace local(test::net_of(mesh, f));
    for (double u : {0.0, 2e-3, 0.3, 0.5, 0.77, 0.998, 1.0})
      for (double v : {0.0, 2e-3, 0.45, 0.998, 1.0}) {
        double h[12], e[9];
        local.eval(u, v, h);
        s.eval(f, u, v, e);
        const auto x = test::cartesian(h);
        const test::LimitSample o = osd.eval(f, u, v);
        const bool corner = (u == 0 || u == 1) && (v == 0 || v == 1);  // derivatives there: directions
        for (std::size_t k = 0; k < 3; ++k) {
          to_osd = std::max(to_osd, std::abs(x[k] - o.p[k]));
          to_surface = std::max(to_surface, std::abs(x[k] - e[k]));
          if (corner) continue;
          to_osd = std::max({to_osd, std::abs(x[3 + k] - o.du[k]), std::abs(x[6 + k] - o.dv[k])});
          to_surface = std::max({to_surface, std::abs(x[3 + k] - e[3 + k]), std::abs(x[6 + k] - e[6 + k])});
        }
      }
  }
  EXPECT_GE(faces, 4);  // the top's ends and the end sides' top faces at least
  EXPECT_LT(to_osd, 1e-12);
  EXPECT_LT(to_surface, 1e-12);
  std::printf("open box 5 x 1 x 7, equal intervals: local subdivision of the %d faces with several star corners against "
              "OpenSubdiv %.1e, against the subdivided faces %.1e\n", faces, to_osd, to_surface);
}

// A Bezier rim within two rings of the star points' faces, unequal intervals: the rim gets the ghost layer of its
// end condition, and local non-uniform subdivision runs on the mesh with that layer (no global steps on an open
// mesh). One smooth surface with one boundary loop.
TEST(GlobalNurccStep, CloseStarPointsNearABezierBoundaryTakeItsGhostLayer) {
  const TMesh mesh = stepped_box({3, 3, 2}, true, 1, 1.5);
  const TMeshSurface s(mesh, 1);
  EXPECT_EQ(s.global_steps(), 0);
  EXPECT_GT(s.count(FaceMethod::crease), 0);
  EXPECT_EQ(s.count(FaceMethod::exact), 0);
  const test::Continuity c = test::continuity(s.mesh(), [&](int f, double u, double v, double* o) { s.eval(f, u, v, o); });
  EXPECT_LT(c.gap, 1e-12);
  EXPECT_LT(c.normal_angle, 1e-10);
  const TSplineTriangulation t = tessellate(s, 1e-2);
  EXPECT_EQ(test::boundary_loops(t), 1);
  std::printf("open box 3 x 3 x 2 with a strip of 1.5: %d faces by local subdivision on the ghost layer, %d bicubic; %d edges: gap %.2e, "
              "normal defect (sin) %.2e\n", s.count(FaceMethod::crease), s.count(FaceMethod::bicubic), c.edges, c.gap, c.normal_angle);
}

TEST(GlobalNurccStep, OpenMeshesAreRefused) {
  const test::QuadMesh q = test::fan_mesh(5, 4, [](double, double) { return 0.0; });
  const TMesh mesh = io::parse_tsm(test::tsm_text(q), "fan.tsm").mesh;
  try {
    nurcc_step(mesh);
    ADD_FAILURE() << "stepped an open mesh";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    EXPECT_NE(msg.find("global non-uniform Catmull-Clark step: edge"), std::string::npos) << msg;
    EXPECT_NE(msg.find("is on the boundary (closed meshes only)"), std::string::npos) << msg;
  }
}

}  // namespace
}  // namespace trivar
