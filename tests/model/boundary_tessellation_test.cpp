#include "trivar/model/boundary_tessellation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "trivar/core/error.hpp"
#include "trivar/io/stl_writer.hpp"
#include "trivar/model/block.hpp"
#include "trivar/model/brep_from_surfaces.hpp"
#include "trivar/model/revolve.hpp"
#include "trivar/spline/iso_extraction.hpp"
#include "trivar/spline/reparametrization.hpp"

using namespace trivar;

namespace {

std::vector<TensorSpline<2>> faces_of(const TensorSpline<3>& v) {
  const auto f = boundary_faces(v);
  return {f.begin(), f.end()};
}

// A 270 degree ring: radii 1 and 2, height 1, exact rational in the angular direction.
TensorSpline<3> ring() {
  const TensorSpline<2> profile = make_rectangle_profile({0.0, 1.0}, {1.0, 2.0}, {2, 2}, {1, 2});
  return revolve<3>(profile, {0, 0, 0}, {0, 0, 1}, 1.5 * std::numbers::pi);
}

double radius(const std::array<double, 3>& x) { return std::hypot(x[0], x[1]); }

}  // namespace

TEST(BoundaryTessellation, CubeIsClosedWithExactAreaAndVolume) {
  const TensorSpline<3> cube = make_block<3>({2, 2, 2}, {2, 3, 1}, {1.0, 2.0, 3.0});
  const Brep brep = brep_from_surfaces(faces_of(cube));
  EXPECT_EQ(brep.faces.size(), 6u);
  EXPECT_EQ(brep.curves.size(), 12u);
  EXPECT_EQ(brep.num_vertices, 8);
  const BrepTessellation t = tessellate(brep, {.chordal_tolerance = 1e-3});
  EXPECT_TRUE(is_watertight(t.mesh));
  EXPECT_NEAR(surface_area(t.mesh), 2 * (2 + 6 + 3), 1e-12);
  EXPECT_NEAR(enclosed_volume(t.mesh), 6.0, 1e-12);
  EXPECT_EQ(t.origins.size(), t.mesh.vertices.size());
}

TEST(BoundaryTessellation, ReversedFacesAreTurnedOutwards) {
  // Faces in another order, two of them reparametrised (normal turned inwards, sides reversed): the faces
  // must still come out oriented outwards.
  const TensorSpline<3> cube = make_block<3>({1, 1, 1}, {1, 1, 1}, {1.0, 1.0, 1.0});
  std::vector<TensorSpline<2>> faces = faces_of(cube);
  std::swap(faces[0], faces[5]);
  faces[1] = swap_directions(faces[1], 0, 1);
  faces[3] = reverse(faces[3], 1);
  const BrepTessellation t = tessellate(brep_from_surfaces(faces));
  EXPECT_TRUE(is_watertight(t.mesh));
  EXPECT_NEAR(enclosed_volume(t.mesh), 1.0, 1e-14);
}

TEST(BoundaryTessellation, RingMeetsTheChordalToleranceAndConverges) {
  const double exact = 0.75 * std::numbers::pi * (4.0 - 1.0) * 1.0;
  double previous_error = 1.0;
  for (double tol : {1e-2, 1e-3, 1e-4}) {
    const BrepTessellation t = tessellate(brep_from_surfaces(faces_of(ring())), {.chordal_tolerance = tol});
    ASSERT_TRUE(is_watertight(t.mesh)) << tol;
    // Vertices lie on the exact surface: the cylinders' radii are met to rounding.
    for (const auto& x : t.mesh.vertices) {
      const double r = radius(x);
      if (std::abs(r - 2.0) < 1e-6) {
        EXPECT_NEAR(r, 2.0, 1e-13);
      }
    }
    // Triangles on the outer cylinder stay within the tolerance of it (chordal error at their centroids).
    double worst = 0;
    for (const auto& tri : t.mesh.triangles) {
      bool outer = true;
      std::array<double, 3> c{};
      for (int v : tri) {
        outer = outer && std::abs(radius(t.mesh.vertices[v]) - 2.0) < 1e-9;
        for (int k = 0; k < 3; ++k) c[k] += t.mesh.vertices[v][k] / 3;
      }
      if (outer) worst = std::max(worst, 2.0 - radius(c));
    }
    EXPECT_LE(worst, tol) << tol;
    EXPECT_GT(worst, 0.0);
    const double error = std::abs(enclosed_volume(t.mesh) - exact);
    EXPECT_LT(error, previous_error) << tol;
    EXPECT_LT(error / exact, 10 * tol) << tol;
    previous_error = error;
  }
}

TEST(BoundaryTessellation, OpenOrInconsistentInputFails) {
  const TensorSpline<3> cube = make_block<3>({1, 1, 1}, {1, 1, 1}, {1.0, 1.0, 1.0});
  std::vector<TensorSpline<2>> faces = faces_of(cube);
  faces.pop_back();
  EXPECT_THROW(brep_from_surfaces(faces), Error);
  EXPECT_NO_THROW(brep_from_surfaces(faces, {.require_closed = false}));
  faces = faces_of(cube);
  faces.push_back(faces[0]);  // a third face on the same edges
  EXPECT_THROW(brep_from_surfaces(faces), Error);

  Brep bad = brep_from_surfaces(faces_of(cube));
  bad.faces[0].sides[2].curve = 99;
  EXPECT_THROW(tessellate(bad), Error);
  EXPECT_THROW(tessellate(brep_from_surfaces(faces_of(cube)), {.chordal_tolerance = 0.0}), Error);
}

TEST(StlWriter, BinaryLayoutAndNormals) {
  const BrepTessellation t = tessellate(brep_from_surfaces(faces_of(make_block<3>({1, 1, 1}, {1, 1, 1}, {1.0, 1.0, 1.0}))));
  const auto path = std::filesystem::temp_directory_path() / "trivar_stl_test.stl";
  io::write_stl(path.string(), t.mesh);
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  const std::string bytes = ss.str();
  std::filesystem::remove(path);
  ASSERT_EQ(bytes.size(), 84 + 50 * t.mesh.triangles.size());
  std::uint32_t count = 0;
  std::memcpy(&count, bytes.data() + 80, 4);
  EXPECT_EQ(count, t.mesh.triangles.size());
  for (std::size_t i = 0; i < count; ++i) {
    float v[12];
    std::memcpy(v, bytes.data() + 84 + 50 * i, sizeof v);
    // Unit cube: each facet normal is a unit axis vector pointing away from the centre.
    EXPECT_NEAR(std::abs(v[0]) + std::abs(v[1]) + std::abs(v[2]), 1.0f, 1e-6f);
    const float centre[3] = {(v[3] + v[6] + v[9]) / 3 - 0.5f, (v[4] + v[7] + v[10]) / 3 - 0.5f,
                             (v[5] + v[8] + v[11]) / 3 - 0.5f};
    EXPECT_GT(v[0] * centre[0] + v[1] * centre[1] + v[2] * centre[2], 0.0f);
  }
  TriangleMesh broken = t.mesh;
  broken.triangles[0][1] = 1000;
  EXPECT_THROW(io::write_stl(path.string(), broken), Error);
  EXPECT_FALSE(std::filesystem::exists(path));
}
