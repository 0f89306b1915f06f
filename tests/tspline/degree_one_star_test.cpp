// Degree-1 T-splines with star points: a blending function restricted to a face is its hat on that face's own
// knots, so every face is bilinear in its corners, and a face with a T-junction X in the middle of a side is that
// plus (X - the side's midpoint) times X's hat, star point or not. Checked in closed form on a cube of 3 x 3 faces
// per side (eight valence-3 star points) with its corner face split 2 x 2 and the new points moved off the faces.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "face_continuity.hpp"
#include "fusion_cages.hpp"
#include "star_mesh_tsm.hpp"
#include "support/temp_dir.hpp"
#include "triangulation_loops.hpp"
#include "trivar/io/tsm_format.hpp"
#include "trivar/tspline/t_mesh_surface.hpp"
#include "trivar/tspline/t_mesh_tessellation.hpp"

namespace trivar {
namespace {

TEST(DegreeOneStarPoints, EveryFaceIsBilinearInItsCornersAndTJunctions) {
  test::QuadMesh cube = test::box_mesh({3, 3, 3});
  std::vector<std::array<double, 3>> unbent = cube.points;
  for (auto& p : cube.points) p = {p[0] + 0.1 * std::sin(2 * p[1] + p[2]), p[1] + 0.08 * std::cos(3 * p[0]), p[2] + 0.05 * p[0] * p[1]};
  const std::size_t before = cube.points.size();
  test::split_top_face(cube, unbent, 3, 0, 0, 0);
  for (std::size_t v = before; v < cube.points.size(); ++v) cube.points[v][2] += 0.07 + 0.02 * static_cast<double>(v - before);
  std::string text = test::tsm_text(cube);
  text.replace(text.find("degree 3"), 8, "degree 1");
  const TMesh mesh = io::parse_tsm(text, "cube.tsm").mesh;
  const TMeshSurface s(mesh, 1);
  EXPECT_EQ(s.stars().size(), 8u);
  EXPECT_EQ(s.count(FaceMethod::exact), s.num_faces());
  const auto point = [&](int v) { return mesh.points[static_cast<std::size_t>(mesh.vertices[static_cast<std::size_t>(v)].primary)].xyz; };
  double worst = 0, derivatives = 0;
  int t_faces = 0;
  for (int f = 0; f < s.num_faces(); ++f) {
    const auto c = s.corners(f);
    // The T-junction on the face's side k (corner k to corner k + 1), if any.
    int x = -1, side = -1;
    for (int l : mesh.faces[static_cast<std::size_t>(f)])
      if (mesh.links[static_cast<std::size_t>(l)].flag == 1) x = mesh.links[static_cast<std::size_t>(l)].vertex;
    for (int k = 0; k < 4 && x >= 0; ++k) {
      const int a = c[static_cast<std::size_t>(k)];
      const auto& loop = mesh.faces[static_cast<std::size_t>(f)];
      for (std::size_t i = 0; i < loop.size(); ++i)
        if (mesh.links[static_cast<std::size_t>(loop[i])].vertex == a && mesh.links[static_cast<std::size_t>(loop[(i + 1) % loop.size()])].vertex == x) side = k;
    }
    t_faces += x >= 0;
    for (double u : {0.0, 0.2, 0.5, 0.9, 1.0})
      for (double v : {0.0, 0.35, 0.7, 1.0}) {
        double o[9];
        s.eval(f, u, v, o);
        const std::array<double, 4> sigma{u, v, 1 - u, 1 - v}, tau{v, 1 - u, 1 - v, u};
        for (std::size_t k = 0; k < 3; ++k) {
          const double p0 = point(c[0])[k], p1 = point(c[1])[k], p2 = point(c[2])[k], p3 = point(c[3])[k];
          double b = (1 - u) * (1 - v) * p0 + u * (1 - v) * p1 + u * v * p2 + (1 - u) * v * p3;
          if (x >= 0) {
            const double a = point(c[static_cast<std::size_t>(side)])[k], e = point(c[static_cast<std::size_t>((side + 1) % 4)])[k];
            const double sg = sigma[static_cast<std::size_t>(side)], tu = tau[static_cast<std::size_t>(side)];
            b += (point(x)[k] - (a + e) / 2) * (1 - std::abs(2 * sg - 1)) * (1 - tu);
          } else {
            const double du = (1 - v) * (p1 - p0) + v * (p2 - p3), dv = (1 - u) * (p3 - p0) + u * (p2 - p1);
            derivatives = std::max({derivatives, std::abs(o[3 + k] - du), std::abs(o[6 + k] - dv)});
          }
          worst = std::max(worst, std::abs(o[k] - b));
        }
      }
  }
  EXPECT_EQ(t_faces, 4);
  EXPECT_LT(worst, 1e-14);
  EXPECT_LT(derivatives, 1e-13);
  const test::Continuity cont = test::continuity(s.mesh(), [&](int f, double u, double v, double* o) { s.eval(f, u, v, o); });
  EXPECT_LT(cont.gap, 1e-14);
  EXPECT_EQ(test::closed_euler_characteristic(tessellate(s, 0.01)), 2);
  // The command line says so.
  const test::TempDir dir;
  {
    std::ofstream(dir.file("cube.tsm")) << text;
  }
  const std::string info = test::run_cli(dir, "info " + dir.file("cube.tsm"));
  EXPECT_NE(info.find("degree 1"), std::string::npos) << info;
  EXPECT_NE(info.find("C0 across every edge (degree 1"), std::string::npos) << info;
  std::printf("degree-1 cube of 3 x 3 faces with a split corner face: %d faces (%d with a T-junction) against the closed form %.1e "
              "(derivatives %.1e); across %d edges gap %.1e\n", s.num_faces(), t_faces, worst, derivatives, cont.edges, cont.gap);
}

}  // namespace
}  // namespace trivar
