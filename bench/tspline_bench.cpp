// T-splines: TSM load + build (parse, three layers, blending functions, Bezier extraction), evaluation in
// points per second (one thread) on a 200 x 200 grid over the domain, crack-free tessellation to 1e-3 of the
// bounding box diagonal. The models are the directory in
// TRIVAR_TSM_DIR (e.g. the Rhino exports published with the seed-002 prototype); the hand-written patch of the
// tests is always measured. Analysis: the space of a planar analysis-suitable T-spline (n x n cells, one line
// stopping halfway: a T-junction) from its Bezier extraction, and the Poisson solve on it (f = 1, u = 0).
// Star points: the closed cube of 3 x 3 faces per side (eight valence-3 star points) and the valence-5 fan of
// 5 x 10 x 10 faces (tests/tspline/star_mesh_tsm.hpp): parse + per-face surface build, evaluation on a 16 x 16
// grid per face (all faces, and the faces at star points alone: the Catmull-Clark subdivision path), and the
// watertight tessellation; their Bezier patches (t_mesh_patches); Poisson on the planar valence-5 fan of
// 5 x 8 x 8 faces in the C0 multipatch space of its faces (t_mesh_space). The fan's surface build with a
// subdivision-crease boundary against Bezier end conditions (crease_build).
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "trivar/iga/refined_poisson.hpp"
#include "trivar/iga/solver.hpp"
#include "trivar/iga/surface_poisson.hpp"
#include "trivar/iga/t_mesh_space.hpp"
#include "trivar/iga/tensor_space.hpp"
#include "trivar/io/tsm_format.hpp"
#include "../tests/tspline/star_mesh_tsm.hpp"
#include "trivar/tspline/local_knots.hpp"
#include "trivar/tspline/t_mesh_patches.hpp"
#include "trivar/tspline/t_mesh_surface.hpp"
#include "trivar/tspline/t_mesh_tessellation.hpp"
#include "trivar/tspline/t_mesh_builder.hpp"
#include "trivar/tspline/t_spline_surface.hpp"
#include "trivar/tspline/t_spline_tessellation.hpp"

namespace {

std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

void load_build(benchmark::State& state, const std::string& path) {
  const std::string text = slurp(path);
  for (auto _ : state) {
    const trivar::TSplineSurface s(trivar::io::parse_tsm(text, path).spline, 1);
    benchmark::DoNotOptimize(s.elements().data());
  }
}

void evaluate(benchmark::State& state, const std::string& path) {
  const trivar::TSplineSurface s(trivar::io::read_tsm(path).spline, 1);
  std::vector<trivar::Param<2>> u;
  const auto d = s.domain();
  for (int j = 0; j < 200; ++j)
    for (int i = 0; i < 200; ++i)
      u.push_back({d.lo[0] + (i + 0.5) / 200 * d.extent(0), d.lo[1] + (j + 0.5) / 200 * d.extent(1)});
  std::vector<double> out(u.size() * 3);
  for (auto _ : state) {
    s.eval_many(u, out, 1);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(u.size()));
}

// Tessellation to a chordal tolerance of 1e-3 of the bounding box diagonal (one thread).
void tessellation(benchmark::State& state, const std::string& path) {
  const trivar::TSplineSurface s(trivar::io::read_tsm(path).spline, 1);
  trivar::Box<3> b = trivar::Box<3>::empty();
  for (const auto& e : s.bezier_elements())
    for (std::size_t i = 0; i < e.coefs.size(); i += 4) {
      const double x[3] = {e.coefs[i] / e.coefs[i + 3], e.coefs[i + 1] / e.coefs[i + 3], e.coefs[i + 2] / e.coefs[i + 3]};
      b.extend(x);
    }
  std::size_t triangles = 0;
  for (auto _ : state) {
    const auto m = trivar::tessellate(s, 1e-3 * b.diagonal(), 64, 1);
    triangles = m.triangles.size();
    benchmark::DoNotOptimize(m.points.data());
  }
  state.counters["triangles"] = static_cast<double>(triangles);
}

trivar::TSplineSurface t_junction_square(int n) {
  using namespace trivar;
  std::vector<KnotSegment> g;
  for (int i = 0; i <= n; ++i) {
    const double x = double(i) / n;
    g.push_back({{0.0, x}, {1.0, x}});
    g.push_back({{x, 0.0}, {x, i == n / 2 ? 0.5 : 1.0}});
  }
  TSpline ts = t_spline_from_segments({3, 3}, g, [](double, double, int, int) { return RationalPoint{}; });
  place_at_greville_points(ts);
  return TSplineSurface(ts, 1);
}

void analysis_space(benchmark::State& state) {
  const trivar::TSplineSurface s = t_junction_square(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    const auto space = trivar::refined_space(s, 1);
    benchmark::DoNotOptimize(space.elements.data());
  }
  state.counters["functions"] = static_cast<double>(s.basis().size());
}
BENCHMARK(analysis_space)->Arg(16)->Arg(64)->Unit(benchmark::kMillisecond);

void poisson_solve(benchmark::State& state) {
  const trivar::TSplineSurface s = t_junction_square(static_cast<int>(state.range(0)));
  const auto space = trivar::refined_space(s, 1);
  trivar::PoissonProblem<2> pb;
  pb.source = [](const double*) { return 1.0; };
  pb.dirichlet.push_back({trivar::all_faces<2>(), {}, nullptr});
  for (auto _ : state) {
    auto solver = trivar::make_solver("cholmod");
    const auto r = trivar::solve_poisson(space, pb, *solver, 1);
    benchmark::DoNotOptimize(r.coefs.data());
  }
}
BENCHMARK(poisson_solve)->Arg(16)->Arg(64)->Unit(benchmark::kMillisecond);

std::string star_model(int which) {
  using namespace trivar::test;
  return which == 0 ? tsm_text(cube_mesh(3))
                    : tsm_text(fan_mesh(5, 10, [](double x, double y) { return 0.05 * x * x - 0.03 * x * y; }));
}

// Parse and build the per-face surface of a TSM text, per iteration.
void build_surface(benchmark::State& state, const std::string& text) {
  for (auto _ : state) {
    const trivar::TMeshSurface s(trivar::io::parse_tsm(text, "model.tsm").mesh, 1);
    benchmark::DoNotOptimize(s.num_faces());
  }
}

void star_build(benchmark::State& state) { build_surface(state, star_model(static_cast<int>(state.range(0)))); }
BENCHMARK(star_build)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// 16 x 16 points on each of `faces`, per iteration.
void eval_face_list(benchmark::State& state, const trivar::TMeshSurface& s, const std::vector<int>& faces) {
  double out[9];
  for (auto _ : state)
    for (int f : faces)
      for (int j = 0; j < 16; ++j)
        for (int i = 0; i < 16; ++i) {
          s.eval(f, (i + 0.5) / 16, (j + 0.5) / 16, out);
          benchmark::DoNotOptimize(out);
        }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(faces.size()) * 256);
}

// 16 x 16 points on every face with a surface (only the faces of method `only` if `star_only`), per iteration.
void eval_faces(benchmark::State& state, const trivar::TMeshSurface& s, bool star_only,
                trivar::FaceMethod only = trivar::FaceMethod::star) {
  std::vector<int> faces;
  for (int f = 0; f < s.num_faces(); ++f)
    if (s.method(f) != trivar::FaceMethod::none && (!star_only || s.method(f) == only))
      faces.push_back(f);
  eval_face_list(state, s, faces);
}

// range(1) = 1: only the faces at star points.
void star_eval(benchmark::State& state) {
  const trivar::TMeshSurface s(trivar::io::parse_tsm(star_model(static_cast<int>(state.range(0))), "star.tsm").mesh, 1);
  eval_faces(state, s, state.range(1) == 1);
}
BENCHMARK(star_eval)->Args({0, 0})->Args({0, 1})->Args({1, 0})->Args({1, 1})->Unit(benchmark::kMillisecond);

void star_tessellate(benchmark::State& state) {
  const trivar::TMeshSurface s(trivar::io::parse_tsm(star_model(static_cast<int>(state.range(0))), "star.tsm").mesh, 1);
  std::size_t triangles = 0;
  for (auto _ : state) {
    const auto m = trivar::tessellate(s, state.range(0) == 0 ? 3.5e-3 : 4.5e-2);
    triangles = m.triangles.size();
    benchmark::DoNotOptimize(m.points.data());
  }
  state.counters["triangles"] = static_cast<double>(triangles);
}
BENCHMARK(star_tessellate)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// Bezier patches of the star models at the default tolerance (1e-6 of the size): the level search at the star
// points, the exact pieces, the chart elements.
void star_patches(benchmark::State& state) {
  const trivar::TMeshSurface s(trivar::io::parse_tsm(star_model(static_cast<int>(state.range(0))), "star.tsm").mesh, 1);
  std::size_t patches = 0;
  int levels = 0;
  for (auto _ : state) {
    const auto p = trivar::t_mesh_patches(s);
    patches = p.patches.size();
    levels = p.levels;
    benchmark::DoNotOptimize(p.patches.data());
  }
  state.counters["patches"] = static_cast<double>(patches);
  state.counters["levels"] = levels;
}
BENCHMARK(star_patches)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// Poisson (f = 1, u = 0) on the planar valence-5 fan of 5 x 8 x 8 faces in the C0 multipatch space of its faces,
// n x n elements per face: space build (patches, refinement, side matching) and assembly + solve.
std::string planar_fan() {
  return trivar::test::tsm_text(trivar::test::fan_mesh(5, 8, [](double, double) { return 0.0; }));
}

void star_poisson_space(benchmark::State& state) {
  const trivar::TMeshSurface s(trivar::io::parse_tsm(planar_fan(), "fan.tsm").mesh, 1);
  for (auto _ : state) {
    const auto space = trivar::t_mesh_space(s, static_cast<int>(state.range(0)));
    benchmark::DoNotOptimize(space.num_basis);
  }
}
BENCHMARK(star_poisson_space)->Arg(2)->Arg(8)->Unit(benchmark::kMillisecond);

// -lap u = 1, u = 0 on the boundary, assembled and solved by CHOLMOD in every iteration.
void solve_unit_load(benchmark::State& state, const trivar::MultipatchSpace<2>& space) {
  trivar::PoissonProblem<2> pb;
  pb.source = [](const double*) { return 1.0; };
  pb.dirichlet.push_back({space.boundary, {}, nullptr});
  for (auto _ : state) {
    auto solver = trivar::make_solver("cholmod");
    const auto r = trivar::solve_poisson(space, pb, *solver, 1);
    benchmark::DoNotOptimize(r.coefs.data());
  }
  state.counters["functions"] = space.num_basis;
}

void star_poisson_solve(benchmark::State& state) {
  const trivar::TMeshSurface s(trivar::io::parse_tsm(planar_fan(), "fan.tsm").mesh, 1);
  const auto space = trivar::t_mesh_space(s, static_cast<int>(state.range(0)));
  solve_unit_load(state, space);
}
BENCHMARK(star_poisson_solve)->Arg(2)->Arg(8)->Unit(benchmark::kMillisecond);

// The valence-5 fan of star_model(1) with weights 0.6 to 1.8 (rational Catmull-Clark: the rules run on w x and
// on w); range(0) = 1: only the faces at the star point.
void star_eval_rational(benchmark::State& state) {
  trivar::TMesh mesh = trivar::io::parse_tsm(star_model(1), "star.tsm").mesh;
  for (trivar::RationalPoint& p : mesh.points) p.w = 1.2 + 0.6 * std::sin(0.7 * p.xyz[0] + 0.45 * p.xyz[1] + 0.3);
  const trivar::TMeshSurface s(mesh, 1);
  eval_faces(state, s, state.range(0) == 1);
}
BENCHMARK(star_eval_rational)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// The valence-5 fan of star_model(1) with unequal knot intervals (0.6 to 2.5, per spoke and along the spokes):
// non-uniform Catmull-Clark at its star point. range(0) = 1: only its 20 faces (the star point's two rings of
// faces: the subdivision path), 0: all faces.
void non_uniform_star_eval(benchmark::State& state) {
  const auto text = trivar::test::tsm_text(trivar::test::fan_mesh_with_intervals(
      5, 10, [](double x, double y) { return 0.05 * x * x - 0.03 * x * y; },
      [](int k, int i) { return (0.6 + 0.35 * k) * (1 + 0.25 * (i % 3)); }));
  const trivar::TMeshSurface s(trivar::io::parse_tsm(text, "star.tsm").mesh, 1);
  eval_faces(state, s, state.range(0) == 1, trivar::FaceMethod::non_uniform);
}
BENCHMARK(non_uniform_star_eval)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// The cube of 3 x 3 faces per side (8 valence-3 star points three edges apart) with knot interval 1.5 on its
// middle strip of faces round x (range(0) = 1; 0: every interval 1): with unequal intervals two global
// non-uniform Catmull-Clark steps first (864 faces), with equal ones Stam's patches on the 54 faces as given.
// range(0) = 2: the unequal intervals without steps, the 54 faces by local non-uniform subdivision (crease faces).
std::string stepped_box_text(bool unequal) {
  trivar::test::QuadMesh q = trivar::test::cube_mesh(3);
  for (const auto& f : q.quads)
    for (int k = 0; k < 4; ++k) {
      const int a = f[static_cast<std::size_t>(k)], b = f[static_cast<std::size_t>((k + 1) % 4)];
      if (unequal && std::abs(q.points[static_cast<std::size_t>(a)][0] + q.points[static_cast<std::size_t>(b)][0]) < 1e-12 &&
          q.points[static_cast<std::size_t>(a)][0] != q.points[static_cast<std::size_t>(b)][0])
        q.intervals[{a, b}] = 1.5;
    }
  return trivar::test::tsm_text(q);
}

void stepped_box_build(benchmark::State& state) {
  const std::string text = stepped_box_text(state.range(0) >= 1);
  const trivar::TMesh mesh = trivar::io::parse_tsm(text, "box.tsm").mesh;
  for (auto _ : state) {
    const trivar::TMeshSurface s(mesh, 1, state.range(0) == 2 ? 0 : -1);
    benchmark::DoNotOptimize(s.num_faces());
  }
}
BENCHMARK(stepped_box_build)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

// range(0) = 0: Fusion's box with its top centre face split 2 x 2 (tests/data/tsm/fusion/a3_box3_tjunc_ring2_readback.tsm,
// here the cube of 3 x 3 faces per side with a strip of interval 2 at x < -1/3): T-junctions next to the star points'
// faces, whose two lines are completed round the box (tspline/t_junction_lines) before two global steps. 1: the cube
// of 11 x 11 faces per side with top face (4, 1) split (tests/tspline/t_junction_lines_test.cpp): two lines round the
// box across 726 faces (85 vertices inserted), no steps. 2: the same cube with top face (5, 0) split: one line runs
// half a face from the box's edges and crosses four star points' spokes (across_star).
void t_junction_lines_build(benchmark::State& state) {
  const int n = state.range(0) == 0 ? 3 : 11;
  trivar::test::QuadMesh q = trivar::test::cube_mesh(n);
  for (const auto& f : q.quads)
    for (int k = 0; k < 4; ++k) {
      const auto& a = q.points[static_cast<std::size_t>(f[static_cast<std::size_t>(k)])];
      const auto& b = q.points[static_cast<std::size_t>(f[static_cast<std::size_t>((k + 1) % 4)])];
      if (n == 3 && std::max(a[0], b[0]) < -0.3 && a[0] != b[0]) q.intervals[{f[static_cast<std::size_t>(k)], f[static_cast<std::size_t>((k + 1) % 4)]}] = 2;
    }
  const std::array<int, 2> split = state.range(0) == 0 ? std::array<int, 2>{1, 1} : state.range(0) == 1 ? std::array<int, 2>{4, 1} : std::array<int, 2>{5, 0};
  q = trivar::test::split_face(q, trivar::test::top_face(q.points, q, n, split[0], split[1]), {0, 0, 0, 0, 0});
  const trivar::TMesh mesh = trivar::io::parse_tsm(trivar::test::tsm_text(q), "box.tsm").mesh;
  for (auto _ : state) {
    const trivar::TMeshSurface s(mesh, 1);
    benchmark::DoNotOptimize(s.num_faces());
  }
  state.counters["faces"] = trivar::TMeshSurface(mesh, 1).num_faces();
}
BENCHMARK(t_junction_lines_build)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

// 16 x 16 points per face of the box as given (on the 16 refined faces of a stepped face, 4 x 4 each).
void stepped_box_eval(benchmark::State& state) {
  const trivar::TMeshSurface s(trivar::io::parse_tsm(stepped_box_text(state.range(0) >= 1), "box.tsm").mesh, 1, state.range(0) == 2 ? 0 : -1);
  const int n = 16 >> s.global_steps();
  double out[9];
  for (auto _ : state)
    for (int f = 0; f < s.num_faces(); ++f)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          s.eval(f, (i + 0.5) / n, (j + 0.5) / n, out);
          benchmark::DoNotOptimize(out);
        }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * s.num_faces() * n * n);
}
BENCHMARK(stepped_box_eval)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

// The cube of 1 x 1 faces per side (8 valence-3 star points, every face with four star corners): each face through
// one local Catmull-Clark step (subdivided_face). Build (range(0) = 0) or 16 x 16 points per face (1).
void subdivided_cube(benchmark::State& state) {
  const std::string text = trivar::test::tsm_text(trivar::test::cube_mesh(1));
  if (state.range(0) == 0) {
    for (auto _ : state) {
      const trivar::TMeshSurface s(trivar::io::parse_tsm(text, "cube.tsm").mesh, 1);
      benchmark::DoNotOptimize(s.num_faces());
    }
    return;
  }
  const trivar::TMeshSurface s(trivar::io::parse_tsm(text, "cube.tsm").mesh, 1);
  eval_faces(state, s, false);
}
BENCHMARK(subdivided_cube)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// A star point of 5 faces on a straight boundary (half_fan_mesh: 5 sectors of 10 x 10 faces, end-condition blocks
// on the boundary): Catmull-Clark of valence 7 on the mesh with its ghost layer. range(0) = 1: only the faces at
// the star point, 0: all faces; range(1) = 1: every ring of faces its own knot interval (1, 2, 0.5, 1.5, 1, ...),
// so the faces at the star point and their neighbours (20, those range(0) = 1 takes then) are local non-uniform
// subdivision on the ghost layer; the build (ghost layer, charts) is timed by boundary_star_build.
std::string boundary_star_text(bool graded) {
  trivar::test::QuadMesh q = trivar::test::half_fan_mesh(5, 10, [](double x, double y) { return 0.05 * x * x - 0.03 * x * y; });
  if (graded) trivar::test::grade_by_ring(q, std::vector<std::array<int, 2>>(5, {10, 10}), {1, 2, 0.5, 1.5, 1, 1, 1, 1, 1, 1});
  return trivar::test::tsm_text(q);
}

void boundary_star_eval(benchmark::State& state) {
  const bool graded = state.range(1) == 1;
  const trivar::TMeshSurface s(trivar::io::parse_tsm(boundary_star_text(graded), "boundary_star.tsm").mesh, 1);
  eval_faces(state, s, state.range(0) == 1, graded ? trivar::FaceMethod::crease : trivar::FaceMethod::star);
}
BENCHMARK(boundary_star_eval)->Args({0, 0})->Args({1, 0})->Args({0, 1})->Args({1, 1})->Unit(benchmark::kMillisecond);

void boundary_star_build(benchmark::State& state) {
  const auto text = boundary_star_text(state.range(0) == 1);
  for (auto _ : state) {
    const trivar::TMeshSurface s(trivar::io::parse_tsm(text, "boundary_star.tsm").mesh, 1);
    benchmark::DoNotOptimize(s.boundary_star_faces());
  }
}
BENCHMARK(boundary_star_build)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// The cube of 3 x 3 faces per side (eight valence-3 star points, star_build/0 at degree 3) at degree range(0) = 5
// or 7: every face is averaging subdivision (local subdivision of its (p + 1) / 2 face rings).
std::string averaging_cube(int degree) {
  std::string text = trivar::test::tsm_text(trivar::test::cube_mesh(3));
  return text.replace(text.find("degree 3"), 8, "degree " + std::to_string(degree));
}

void averaging_build(benchmark::State& state) { build_surface(state, averaging_cube(static_cast<int>(state.range(0)))); }
BENCHMARK(averaging_build)->Arg(5)->Arg(7)->Unit(benchmark::kMillisecond);

void averaging_eval(benchmark::State& state) {
  const trivar::TMeshSurface s(trivar::io::parse_tsm(averaging_cube(static_cast<int>(state.range(0))), "cube.tsm").mesh, 1);
  eval_faces(state, s, false);
}
BENCHMARK(averaging_eval)->Arg(5)->Arg(7)->Unit(benchmark::kMillisecond);

// The per-face surface of the valence-5 fan of 5 x 10 x 10 faces from its parsed mesh: range(0) = 0 with Bezier
// end conditions (block points on the boundary), 1 as a subdivision-crease boundary (no blocks; crease_ends
// converts it to Bezier end conditions first).
void crease_build(benchmark::State& state) {
  trivar::TMesh m = trivar::io::parse_tsm(star_model(1), "fan.tsm").mesh;
  if (state.range(0) == 1) {
    m.end_conditions = trivar::EndConditions::subd_creases;
    for (trivar::TMeshVertex& v : m.vertices) {
      v.block.clear();
      v.block_dims = {};
    }
  }
  for (auto _ : state) {
    const trivar::TMeshSurface s(m, 1);
    benchmark::DoNotOptimize(s.num_faces());
  }
}
BENCHMARK(crease_build)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// A parsed mesh as a subdivision-crease mesh without end-condition blocks (Fusion's SUBD_CREASES).
trivar::TMesh crease_mesh(const std::string& text) {
  trivar::TMesh m = trivar::io::parse_tsm(text, "crease.tsm").mesh;
  m.end_conditions = trivar::EndConditions::subd_creases;
  for (trivar::TMeshVertex& v : m.vertices) {
    v.block.clear();
    v.block_dims = {};
  }
  return m;
}

// The faces by local subdivision with an irregular corner.
std::vector<int> irregular_corner_faces(const trivar::TMeshSurface& s) {
  std::vector<int> faces;
  for (int f = 0; f < s.num_faces(); ++f)
    if (s.method(f) == trivar::FaceMethod::crease)
      for (int c = 0; c < 4; ++c)
        if (s.crease_face(f).irregular(c)) {
          faces.push_back(f);
          break;
        }
  return faces;
}

// A subdivision-crease mesh's surface: what = 0: the build; 1: 16 x 16 points on the faces by local subdivision;
// 2: on all faces; 3: on the faces at its irregular vertices.
void crease_surface_bench(benchmark::State& state, const trivar::TMesh& m, std::int64_t what) {
  if (what == 0) {
    for (auto _ : state) {
      const trivar::TMeshSurface s(m, 1);
      benchmark::DoNotOptimize(s.num_faces());
    }
    return;
  }
  const trivar::TMeshSurface s(m, 1);
  if (what < 3)
    eval_faces(state, s, what == 1, trivar::FaceMethod::crease);
  else
    eval_face_list(state, s, irregular_corner_faces(s));
}

// The star point of 5 faces on a straight boundary of boundary_star_eval as a subdivision-crease boundary (no
// blocks): a crease vertex of 5 faces, its faces within 4 rings by local subdivision (crease_face). range(0) = 0:
// the build; 1: 16 x 16 points on the faces by local subdivision; 2: on all faces; 3: on the 5 faces at the vertex;
// 4 and 5: the build and the faces by local subdivision with unequal knot intervals (the strips of every spoke's
// first two edges at 1.5 and 0.75).
void crease_star(benchmark::State& state) {
  const auto fan = trivar::test::half_fan_mesh(5, 10, [](double x, double y) { return 0.05 * x * x - 0.03 * x * y; });
  trivar::TMesh m = crease_mesh(trivar::test::tsm_text(fan));
  if (state.range(0) >= 4) {
    // A spoke edge (from the vertex at the origin, radius i - 1 to i <= 2) and the rungs of its strip.
    const auto L = [&](int l) -> const trivar::TMeshLink& { return m.links[static_cast<std::size_t>(l)]; };
    const auto radius = [&](int v) { return std::hypot(fan.points[static_cast<std::size_t>(v)][0], fan.points[static_cast<std::size_t>(v)][1]); };
    for (int l = 0; l < static_cast<int>(m.links.size()); ++l) {
      if (L(l).vertex < 0 || L(l).face < 0) continue;
      const int a = L(l).vertex, b = L(L(l).next).vertex;
      const auto& pa = fan.points[static_cast<std::size_t>(a)];
      const auto& pb = fan.points[static_cast<std::size_t>(b)];
      const double ra = radius(a), rb = radius(b);
      if (std::abs(pa[0] * pb[1] - pa[1] * pb[0]) > 1e-9 || std::abs(std::abs(ra - rb) - 1) > 1e-9 || std::max(ra, rb) > 2.5) continue;
      const double d = std::max(ra, rb) < 1.5 ? 1.5 : 0.75;
      for (int start : {l, L(l).opp})
        for (int k = start; k >= 0 && L(k).face >= 0;) {
          m.intervals[static_cast<std::size_t>(L(k).edge)] = d;
          const int across = L(L(L(k).next).next).opp;
          m.intervals[static_cast<std::size_t>(L(across).edge)] = d;
          k = across;
        }
    }
  }
  crease_surface_bench(state, m, state.range(0) % 4);
}
BENCHMARK(crease_star)->Arg(0)->Arg(1)->Arg(2)->Arg(3)->Arg(4)->Arg(5)->Unit(benchmark::kMillisecond);

// The per-face surface of a grid of 20 x 20 faces (the valence-4 fan) with a crease boundary: range(0) = 0 as it
// is, 1 with a sharp crease along its middle line x = 0 (20 edges; sharp_creases cuts the mesh open before
// crease_ends converts both sides).
void sharp_crease_build(benchmark::State& state) {
  const auto q = trivar::test::fan_mesh(4, 10, [](double x, double y) { return 0.05 * x * x - 0.03 * x * y; });
  trivar::TMesh m = crease_mesh(trivar::test::tsm_text(q));
  const auto on_line = [&](int v) { return std::abs(q.points[static_cast<std::size_t>(v)][0]) < 1e-9; };
  if (state.range(0) == 1)
    for (std::size_t l = 0; l < m.links.size(); ++l) {
      const trivar::TMeshLink& k = m.links[l];
      if (k.vertex >= 0 && static_cast<int>(l) < k.opp && k.face >= 0 && m.links[static_cast<std::size_t>(k.opp)].face >= 0 &&
          on_line(k.vertex) && on_line(m.links[static_cast<std::size_t>(k.opp)].vertex))
        m.conditions.push_back({k.edge, 0});
    }
  for (auto _ : state) {
    const trivar::TMeshSurface s(m, 1);
    benchmark::DoNotOptimize(s.num_faces());
  }
}
BENCHMARK(sharp_crease_build)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// Darts: the grid of sharp_crease_build with a sharp crease of 3 edges from its centre along x = 0, ending inside
// the mesh at both ends (two darts), the faces within 4 rings of them by local subdivision (crease_face).
// range(0) as crease_surface_bench (3: the 8 faces at the darts).
void dart_crease(benchmark::State& state) {
  const auto q = trivar::test::fan_mesh(4, 10, [](double x, double y) { return 0.05 * x * x - 0.03 * x * y; });
  trivar::TMesh m = crease_mesh(trivar::test::tsm_text(q));
  const auto on_crease = [&](int v) {
    const auto& p = q.points[static_cast<std::size_t>(v)];
    return std::abs(p[0]) < 1e-9 && p[1] > -1e-9 && p[1] < 3.5;
  };
  for (std::size_t l = 0; l < m.links.size(); ++l) {
    const trivar::TMeshLink& k = m.links[l];
    if (k.vertex >= 0 && static_cast<int>(l) < k.opp && on_crease(k.vertex) && on_crease(m.links[static_cast<std::size_t>(k.opp)].vertex))
      m.crease_edges.push_back(k.edge);
  }
  crease_surface_bench(state, m, state.range(0));
}
BENCHMARK(dart_crease)->Arg(0)->Arg(1)->Arg(3)->Unit(benchmark::kMillisecond);

// Poisson on the planar valence-5 fan with T-junctions (5 x 8 x 8 faces, three split): the patches cut until
// their sides conform, refined n x n; space build, then assembly + solve.
trivar::TMeshSurface planar_t_fan() {
  return trivar::TMeshSurface(
      trivar::io::parse_tsm(trivar::test::tsm_text(trivar::test::fan_mesh_with_t_junctions(5, 8, 6, 2, 5, [](double, double) { return 0.0; })),
                            "t_fan.tsm")
          .mesh,
      1);
}

void t_junction_poisson_space(benchmark::State& state) {
  const trivar::TMeshSurface s = planar_t_fan();
  for (auto _ : state) {
    const auto space = trivar::t_mesh_space(s, static_cast<int>(state.range(0)));
    benchmark::DoNotOptimize(space.num_basis);
  }
}
BENCHMARK(t_junction_poisson_space)->Arg(2)->Arg(8)->Unit(benchmark::kMillisecond);

void t_junction_poisson_solve(benchmark::State& state) {
  const trivar::TMeshSurface s = planar_t_fan();
  const auto space = trivar::t_mesh_space(s, static_cast<int>(state.range(0)));
  solve_unit_load(state, space);
}
BENCHMARK(t_junction_poisson_solve)->Arg(2)->Arg(8)->Unit(benchmark::kMillisecond);

// -lap_S u + u = 1 on the closed cube surface of eight valence-3 star points (54 faces), n x n elements per face:
// space build and assembly + solve (point by point: basis, metric, one quadrature point at a time).
void surface_poisson(benchmark::State& state) {
  const trivar::TMeshSurface s(trivar::io::parse_tsm(star_model(0), "cube.tsm").mesh, 1);
  int functions = 0;
  for (auto _ : state) {
    const auto space = trivar::t_mesh_surface_space(s, static_cast<int>(state.range(0)));
    trivar::SurfacePoissonProblem pb;
    pb.reaction = 1;
    pb.source = [](const double*) { return 1.0; };
    auto solver = trivar::make_solver("cholmod");
    const auto r = trivar::solve_surface_poisson(space, pb, *solver);
    functions = space.space.num_basis;
    benchmark::DoNotOptimize(r.coefs.data());
  }
  state.counters["functions"] = functions;
}
BENCHMARK(surface_poisson)->Arg(2)->Arg(8)->Unit(benchmark::kMillisecond);

int register_models() {
  std::vector<std::string> files{std::string(TRIVAR_SOURCE_DIR) + "/tests/data/tsm/bezier_patch.tsm"};
  if (const char* dir = std::getenv("TRIVAR_TSM_DIR"))
    for (const auto& e : std::filesystem::directory_iterator(dir))
      if (e.path().extension() == ".tsm") files.push_back(e.path().string());
  for (const std::string& f : files) {
    const std::string name = std::filesystem::path(f).stem().string();
    benchmark::RegisterBenchmark(("tsm_load_build/" + name).c_str(), load_build, f)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("tsm_eval/" + name).c_str(), evaluate, f)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("tsm_tessellate/" + name).c_str(), tessellation, f)->Unit(benchmark::kMillisecond);
  }
  return 0;
}
const int registered = register_models();

}  // namespace
BENCHMARK_MAIN();
