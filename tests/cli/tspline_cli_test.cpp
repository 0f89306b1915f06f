// `trivar info|eval|convert` on T-splines: the hand-written Bezier patch in TSM, converted to both STEP forms,
// JSON, .lr, meshes; malformed input fails with one line and writes nothing; `solve poisson` on a planar
// T-spline written as .tsm and .stp, and on curved models (the surface problem).
#include <map>

#include "cli_fixture.hpp"
#include "trivar/io/spline_file.hpp"
#include "tspline/star_mesh_tsm.hpp"
#include "trivar/io/g2_format.hpp"
#include "trivar/io/tsm_format.hpp"
#include "trivar/tspline/t_spline_surface.hpp"
#include "trivar/tspline/local_knots.hpp"
#include "trivar/tspline/t_mesh_builder.hpp"

namespace {

using namespace cli_test;

class TSplineCli : public Cli {
protected:
  void SetUp() override {
    Cli::SetUp();
    fs::copy_file(std::string(TRIVAR_TEST_DATA) + "/tsm/bezier_patch.tsm", work_ / "patch.tsm");
  }
};

// The patch's value at (0.3, 0.6), from the tensor NURBS the file was written from (tests/tspline).
TEST_F(TSplineCli, InfoEvalAndConversionsAgree) {
  const Result info = ok("info patch.tsm");
  EXPECT_NE(info.out.find("T-spline surface (TSM #TS0200), degrees 3 x 3"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("Part 42 type ANALYSIS_SUITABLE_T_SPLINE"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("100001uv x1"), std::string::npos) << info.out;  // reported, not silently dropped
  const auto p = numbers_after(ok("eval patch.tsm 0.3 0.6").out, "S");
  ASSERT_EQ(p.size(), 3u);
  for (const std::string out : {"patch.stp", "patch42.stp", "patch.json", "patch.lr"}) {
    const std::string form = out == std::string("patch42.stp") ? " --step-form part42" : "";
    ok("convert patch.tsm " + out + form);
    if (out == std::string("patch.lr")) continue;
    const auto q = numbers_after(ok("eval " + out + " 0.3 0.6").out, "S");
    ASSERT_EQ(q.size(), 3u);
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(p[static_cast<std::size_t>(d)], q[static_cast<std::size_t>(d)], 1e-13) << out;
  }
  const auto lr = numbers_after(ok("eval patch.lr 0.3 0.6").out, "S");
  for (int d = 0; d < 3; ++d) EXPECT_NEAR(p[static_cast<std::size_t>(d)], lr[static_cast<std::size_t>(d)], 1e-13);
  ok("convert patch.tsm patch.stl --tolerance 1e-3");
  ok("convert patch.tsm patch.obj");
  ok("convert patch.tsm patch.vtu");
  for (const char* f : {"patch.stl", "patch.obj", "patch.vtu"}) EXPECT_TRUE(fs::exists(work_ / f)) << f;
}

TEST_F(TSplineCli, MalformedTsmFailsWithOneLine) {
  std::string text = slurp(work_ / "patch.tsm");
  text.replace(text.find("l 3 1 4 0 0 0 0"), 15, "l 3 1 40 0 0 0 0");
  std::ofstream(work_ / "bad.tsm") << text;
  fails("info bad.tsm");
  fails("convert bad.tsm bad.stp");
  EXPECT_FALSE(fs::exists(work_ / "bad.stp"));
  fails("eval patch.tsm 2 0.5");  // outside the domain
  fails("convert patch.tsm patch.png");
}

// The unit square as an analysis-suitable bicubic T-spline (8 x 8 cells, the line s = 1/2 stopping at t = 1/2),
// points at the Greville points (the identity map).
trivar::TSpline unit_square_t_spline() {
  using namespace trivar;
  std::vector<KnotSegment> g;
  for (int i = 0; i <= 8; ++i) {
    const double x = i / 8.0;
    g.push_back({{0.0, x}, {1.0, x}});
    g.push_back({{x, 0.0}, {x, i == 4 ? 0.5 : 1.0}});
  }
  TSpline ts = t_spline_from_segments({3, 3}, g, [](double, double, int, int) { return RationalPoint{}; });
  place_at_greville_points(ts);
  return ts;
}

// -lap u = 1 on the unit square, u = 0 on the boundary: u(1/2, 1/2) = 0.0736713532814 (the Fourier series);
// 116 blending functions: the 11 x 11 of the tensor mesh without the 5 of the missing half line (measured
// 0.0736659 at the centre).
TEST_F(TSplineCli, SolvePoissonOnAPlanarTSpline) {
  trivar::io::write_tsm((work_ / "square.tsm").string(), unit_square_t_spline());
  ok("convert square.tsm square.stp");
  for (const char* f : {"square.tsm", "square.stp"}) {
    const Result r = ok(std::string("solve poisson ") + f + " --solver cholmod");
    EXPECT_NE(r.out.find("T-spline space: 116 blending functions"), std::string::npos) << r.out;
    const auto u = numbers_after(r.out, "u at the domain centre");
    ASSERT_FALSE(u.empty()) << r.out;
    EXPECT_NEAR(u[0], 0.0736713532814, 1e-5) << f;
  }
  ok("solve poisson square.tsm --out sol");
  EXPECT_TRUE(fs::exists(work_ / "sol" / "solution.vtu"));
  // A curved model: the Laplace-Beltrami problem on its surface (-lap_S u = 1, u = 0 on the boundary); its
  // solution is a field on the surface, so --out is refused and writes nothing.
  const Result curved = ok("solve poisson patch.tsm --solver cholmod");
  EXPECT_NE(curved.out.find("T-mesh surface (curved, open)"), std::string::npos) << curved.out;
  EXPECT_FALSE(numbers_after(curved.out, "u: max").empty()) << curved.out;
  fails("solve poisson patch.tsm --out curved");
  EXPECT_FALSE(fs::exists(work_ / "curved"));
  fails("solve elasticity square.tsm");
}

// .g2: the Bezier patch (an LR spline) as a GoTools LRSplineSurface, which evaluates as the T-spline; a T-spline
// whose blending functions do not sum to one (crossing T-junction extensions) as rational Bezier patches.
TEST_F(TSplineCli, G2HoldsTheLRSplineOrBezierPatches) {
  const auto p = numbers_after(ok("eval patch.tsm 0.3 0.6").out, "S");
  const Result lr = ok("convert patch.tsm patch.g2");
  EXPECT_NE(lr.out.find("LRSplineSurface"), std::string::npos) << lr.out;
  const auto q = numbers_after(ok("eval patch.g2 0.3 0.6").out, "S");
  ASSERT_EQ(q.size(), 3u);
  for (std::size_t d = 0; d < 3; ++d) EXPECT_NEAR(p[d], q[d], 1e-13);

  using namespace trivar;
  std::vector<KnotSegment> g;
  for (int i = 0; i <= 6; ++i) {
    g.push_back({{0.0, double(i)}, {6.0, double(i)}});
    g.push_back({{double(i), 0.0}, {double(i), i == 3 ? 3.0 : 6.0}});
  }
  g.push_back({{0.0, 3.5}, {2.0, 3.5}});
  g.push_back({{3.5, 0.0}, {3.5, 6.0}});
  const TSpline ts = t_spline_from_segments({3, 3}, g, [](double s, double t, int a, int b) {
    return RationalPoint{{s + 0.2 * a, t - 0.1 * b, std::sin(s) * std::cos(t)}, 1.0};
  });
  io::write_tsm((work_ / "cross.tsm").string(), ts);
  const Result bz = ok("convert cross.tsm cross.g2");
  EXPECT_NE(bz.out.find("rational Bezier patches"), std::string::npos) << bz.out;
  const TSplineSurface surf(ts);
  const auto patches = io::read_g2((work_ / "cross.g2").string());
  ASSERT_EQ(patches.size(), surf.elements().size());
  for (std::size_t e = 0; e < patches.size(); ++e) {
    const auto& patch = std::get<TensorSpline<2>>(patches[e]);
    const Box<2>& b = surf.elements()[e];
    const Param<2> u{b.lo[0] + 0.3 * b.extent(0), b.lo[1] + 0.6 * b.extent(1)};
    double x[3], y[3];
    surf.eval(u, x);
    patch.eval(u, y);
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(x[d], y[d], 1e-12) << e;
  }
}

}  // namespace

namespace {

// The closed cube of 3 x 3 faces per side with its eight valence-3 star points (tests/data/tsm/star_cube.tsm,
// written from tests/tspline/star_mesh_tsm.hpp): info counts the faces by method, eval takes FACE U V, the
// tessellation is closed, forms without star points are refused.
TEST_F(TSplineCli, StarPointModel) {
  fs::copy_file(std::string(TRIVAR_TEST_DATA) + "/tsm/star_cube.tsm", work_ / "cube.tsm");
  const Result info = ok("info cube.tsm");
  EXPECT_NE(info.out.find("54 faces, 8 star points (8 of valence 3)"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("54 faces within 5 rings of a star point"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("24 at a star point"), std::string::npos) << info.out;
  // The centre face of a side is the flat square [-1/3, 1/3]^2 of that side (linear precision).
  const Result e = ok("eval cube.tsm 4 0.5 0.5 --derivs 1");
  const auto p = numbers_after(e.out, "S");
  ASSERT_EQ(p.size(), 3u);
  EXPECT_NEAR(std::abs(p[0]) + std::abs(p[1]) + std::abs(p[2]), 1.0, 1e-14);
  fails("eval cube.tsm 0.5 0.5");
  fails("eval cube.tsm 54 0.5 0.5");
  fails("eval cube.tsm 3 1.5 0.5");
  ok("convert cube.tsm cube.stl --tolerance 1e-3");
  ok("convert cube.tsm cube.obj");
  ok("convert cube.tsm cube2.tsm");
  EXPECT_EQ(numbers_after(ok("eval cube2.tsm 4 0.5 0.5").out, "S"), p);
  // Bezier patches (t_mesh_patches): exact pieces and one corner patch per face at a star point.
  const Result g2 = ok("convert cube.tsm cube.g2 --tolerance 1e-4");
  EXPECT_NE(g2.out.find("24 corner patches at star points"), std::string::npos) << g2.out;
  const auto counts = numbers_after(g2.out, "cube.g2:");
  ASSERT_FALSE(counts.empty()) << g2.out;
  const std::vector<trivar::AnySpline> from_g2 = trivar::io::read_spline_file((work_ / "cube.g2").string());
  EXPECT_EQ(static_cast<double>(from_g2.size()), counts[0]);
  ok("convert cube.tsm cube.stp --tolerance 1e-4");
  ok("convert cube.tsm cube.json --tolerance 1e-4");
  for (const char* f : {"cube.stp", "cube.json"}) {
    const std::vector<trivar::AnySpline> back = trivar::io::read_spline_file((work_ / f).string());
    ASSERT_EQ(back.size(), from_g2.size()) << f;
    double worst = 0;
    for (std::size_t i = 0; i < back.size(); ++i) {
      const auto& a = std::get<trivar::TensorSpline<2>>(from_g2[i]);
      const auto& b = std::get<trivar::TensorSpline<2>>(back[i]);
      ASSERT_EQ(a.coefs().size(), b.coefs().size());
      for (std::size_t k = 0; k < a.coefs().size(); ++k) worst = std::max(worst, std::abs(a.coefs()[k] - b.coefs()[k]));
    }
    EXPECT_LT(worst, 1e-13) << f;
  }
  fails("convert cube.tsm cube.lr");
  fails("convert cube.tsm cube.g2 --tolerance 1e-40");  // beyond the subdivision levels
  // The OBJ is closed: every edge in two triangles.
  std::ifstream obj(work_ / "cube.obj");
  std::map<std::pair<long, long>, int> edges;
  std::string line;
  while (std::getline(obj, line)) {
    if (line.rfind("f ", 0) != 0) continue;
    std::istringstream is(line.substr(2));
    std::vector<long> v;
    std::string w;
    while (is >> w) v.push_back(std::stol(w));
    ASSERT_EQ(v.size(), 3u);
    for (int k = 0; k < 3; ++k) ++edges[{std::min(v[k], v[(k + 1) % 3]), std::max(v[k], v[(k + 1) % 3])}];
  }
  ASSERT_FALSE(edges.empty());
  for (const auto& [k, n] : edges) ASSERT_EQ(n, 2);
}

// The valence-5 fan with unequal knot intervals around its star point: info counts the faces taken by
// non-uniform Catmull-Clark, eval and the Bezier patches run on them.
TEST_F(TSplineCli, NonUniformStarPointModel) {
  std::ofstream((work_ / "fan.tsm").string()) << trivar::test::tsm_text(trivar::test::fan_mesh_with_intervals(
      5, 8, [](double x, double y) { return 0.05 * x * x - 0.03 * x * y; },
      [](int k, int i) { return (0.6 + 0.35 * k) * (1 + 0.25 * (i % 3)); }));
  const Result info = ok("info fan.tsm");
  EXPECT_NE(info.out.find("20 faces around 1 star points with unequal knot intervals by non-uniform Catmull-Clark"),
            std::string::npos) << info.out;
  EXPECT_NE(ok("info fan.tsm --json").out.find("\"faces_non_uniform_catmull_clark\": 20"), std::string::npos);
  EXPECT_EQ(numbers_after(ok("eval fan.tsm 0 0.25 0.5").out, "S").size(), 3u);
  const Result g2 = ok("convert fan.tsm fan.g2");
  EXPECT_NE(g2.out.find("5 corner patches at star points"), std::string::npos) << g2.out;
}

// The cube of 1 x 1 faces per side (four star corners per face): info counts the faces taken through one local
// Catmull-Clark step, the Bezier patches are their quarters', and -lap_S u + u = 1 on the closed surface of those
// patches has the solution u = 1.
TEST_F(TSplineCli, CoarseCageThroughLocalSubdivision) {
  std::ofstream((work_ / "cage.tsm").string()) << trivar::test::tsm_text(trivar::test::cube_mesh(1));
  const Result info = ok("info cage.tsm");
  EXPECT_NE(info.out.find("6 of them with several star corners"), std::string::npos) << info.out;
  EXPECT_NE(ok("info cage.tsm --json").out.find("\"faces_subdivided\": 6"), std::string::npos);
  // The centre of face 0 (the side x = -1) is the limit of its face point F = (-1, 0, 0) after one step, a regular
  // vertex: (16 F + 4 sum E + sum V) / 36 with the edge points E (x = -3/4) and the corners' vertex points
  // V = (1/3) v + (1/9) (sum of neighbours + sum of face points) (x = -5/9): x = -68/81.
  const auto centre = numbers_after(ok("eval cage.tsm 0 0.5 0.5").out, "S");
  ASSERT_EQ(centre.size(), 3u);
  EXPECT_NEAR(centre[0], -68.0 / 81, 1e-15);
  EXPECT_NEAR(centre[1], 0, 1e-15);
  EXPECT_NEAR(centre[2], 0, 1e-15);
  const Result g2 = ok("convert cage.tsm cage.g2");
  EXPECT_NE(g2.out.find("24 corner patches at star points"), std::string::npos) << g2.out;
  const Result c = ok("solve poisson cage.tsm --solver cholmod --refine 2");
  EXPECT_NE(c.out.find("6 faces as 24 patches"), std::string::npos) << c.out;
  const auto one = numbers_after(c.out, "u: max");
  ASSERT_FALSE(one.empty()) << c.out;
  EXPECT_NEAR(one[0], 1.0, 1e-9);
}

// -lap u = 1, u = 0 on the boundary of the planar valence-3 fan of 3 x 8 x 8 faces (star point at the origin):
// the C0 multipatch space of its face patches. The domain lies in the disk of radius 8 around the star point and
// holds the disk of radius 6.5 (its boundary lies 6.78 to 7.84 from it), so by comparison with the disks' solutions
// (R^2 - r^2) / 4 the maximum lies between 10.56 and 16 (12.973 measured; 12.951 with 4 x 4 elements per face).
TEST_F(TSplineCli, SolvePoissonAroundAStarPoint) {
  std::ofstream((work_ / "fan.tsm").string()) << trivar::test::tsm_text(trivar::test::fan_mesh(3, 8, [](double, double) { return 0.0; }));
  const Result r = ok("solve poisson fan.tsm --solver cholmod --refine 1 --out sol");
  EXPECT_NE(r.out.find("192 faces as 192 patches"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("3 corner patches"), std::string::npos) << r.out;
  const auto u = numbers_after(r.out, "u: max");
  ASSERT_FALSE(u.empty()) << r.out;
  EXPECT_GT(u[0], 6.5 * 6.5 / 4);
  EXPECT_LT(u[0], 16.0);
  EXPECT_TRUE(fs::exists(work_ / "sol" / "solution.vtu"));
  fs::copy_file(std::string(TRIVAR_TEST_DATA) + "/tsm/star_cube.tsm", work_ / "cube.tsm");
  // The closed cube surface: -lap_S u + u = 1, whose solution is u = 1 (in the space: the partition of unity).
  const Result c = ok("solve poisson cube.tsm --solver cholmod --refine 2");
  EXPECT_NE(c.out.find("T-mesh surface (curved, closed)"), std::string::npos) << c.out;
  const auto one = numbers_after(c.out, "u: max");
  ASSERT_FALSE(one.empty()) << c.out;
  EXPECT_NEAR(one[0], 1.0, 1e-9);
}

}  // namespace
