// Booleans of V-models: volumes against closed forms, the robustness cases (coincident faces, tangent contact,
// one operand inside the other, disjoint operands, results as operands), the topology of the result and the
// attribute blends.
#include <gtest/gtest.h>

#include <cstdio>
#include <numbers>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "trivar/am/layer_slicer.hpp"
#include "trivar/am/slicer.hpp"
#include "trivar/cad/boolean.hpp"
#include "trivar/io/vmodel_json.hpp"
#include "trivar/model/ball.hpp"
#include "trivar/model/cylinder.hpp"
#include "trivar/model/primitives.hpp"
#include "trivar/model/torus.hpp"
#include "trivar/model/trimmed_tessellation.hpp"
#include "trivar/spline/affine_transform.hpp"
#include "support/model_fixtures.hpp"

using namespace trivar;
using cad::BooleanOp;

namespace {

using std::numbers::pi;

VModel box(const Eigen::Vector3d& lo, const Eigen::Vector3d& size) { return test::glued(make_box({size, lo})); }

VModel ball(double r, const Eigen::Vector3d& c = Eigen::Vector3d::Zero()) { return test::glued(make_ball({r, c})); }

void set_constant(VModel& m, const std::string& name, std::vector<double> v) {
  for (int c = 0; c < m.num_cells(); ++c) m.cell(c).set_attribute(name, Attribute::constant(v));
}

// Boundary of the result: watertight, and its Euler characteristic.
int boundary_euler(const VModel& m) {
  const ModelTessellation t = trimmed_boundary_mesh(m);
  EXPECT_TRUE(is_watertight(t.mesh));
  return euler_characteristic(t.mesh);
}

// Every face between two result cells is shared by exactly two (the kernel's pieces meet face to face), so the
// neighbour lists are symmetric.
void expect_symmetric_neighbours(const cad::BooleanReport& r) {
  ASSERT_EQ(static_cast<int>(r.neighbours.size()), r.cells);
  for (int c = 0; c < r.cells; ++c)
    for (int n : r.neighbours[static_cast<std::size_t>(c)]) {
      EXPECT_NE(n, c);
      const auto& back = r.neighbours[static_cast<std::size_t>(n)];
      EXPECT_TRUE(std::find(back.begin(), back.end(), c) != back.end());
    }
}

}  // namespace

// A ball with a cylindrical hole through its centre (the napkin ring): (4/3) pi (R^2 - r^2)^(3/2).
TEST(Boolean, BallMinusCylinderIsTheNapkinRing) {
  const double R = 1, r = 0.4;
  const VModel b = ball(R);
  const VModel cyl = test::glued(make_cylinder({r, 3}), {0, 0, -1.5});
  cad::BooleanReport rep;
  const VModel ring = cad::boolean(b, cyl, BooleanOp::subtract, {}, &rep);
  const double exact = 4.0 / 3 * pi * std::pow(R * R - r * r, 1.5);
  EXPECT_NEAR(ring.volume(), exact, 1e-8 * exact);
  EXPECT_EQ(rep.cells_a, 7);
  EXPECT_EQ(rep.cells, rep.pieces_a_only);
  EXPECT_EQ(boundary_euler(ring), 0);  // a torus-like surface: genus 1
  expect_symmetric_neighbours(rep);
}

// Two unit balls one radius apart: the lens (intersection) is pi (4R + d)(2R - d)^2 / 12, the union
// vol(A) + vol(B) - lens; the union's boundary is one sphere-like surface.
TEST(Boolean, OverlappingBallsLensAndUnion) {
  const double R = 1, d = 1;
  const VModel a = ball(R), b = ball(R, {d, 0, 0});
  const double lens = pi * (4 * R + d) * (2 * R - d) * (2 * R - d) / 12;
  cad::BooleanReport rep;
  const VModel u = cad::boolean(a, b, BooleanOp::unite, {}, &rep);
  EXPECT_NEAR(u.volume(), a.volume() + b.volume() - lens, 1e-8 * u.volume());
  EXPECT_NEAR(a.volume(), 4.0 / 3 * pi, 1e-10);
  EXPECT_EQ(rep.cells, rep.pieces);
  EXPECT_GT(rep.pieces_both, 0);
  EXPECT_EQ(boundary_euler(u), 2);
  expect_symmetric_neighbours(rep);
  const VModel i = cad::boolean(a, b, BooleanOp::intersect);
  EXPECT_NEAR(i.volume(), lens, 1e-8 * lens);
  EXPECT_EQ(boundary_euler(i), 2);
}

// A torus with a quadrant removed by a box: three quarters of 2 pi^2 R r^2, one sphere-like boundary.
TEST(Boolean, TorusMinusBox) {
  const double R = 2, r = 0.5;
  const VModel t = test::glued(make_torus({R, r}));
  const VModel q = box({0, 0, -1}, {3, 3, 2});
  const VModel cut = cad::boolean(t, q, BooleanOp::subtract);
  const double exact = 0.75 * 2 * pi * pi * R * r * r;
  EXPECT_NEAR(cut.volume(), exact, 1e-8 * exact);
  EXPECT_EQ(boundary_euler(cut), 2);
}

// Coincident faces: two unit cubes sharing a face fuse into a 2 x 1 x 1 block of two cells that are
// neighbours across that one face.
TEST(Boolean, CubesSharingAFace) {
  cad::BooleanReport rep;
  const VModel u = cad::boolean(box({0, 0, 0}, {1, 1, 1}), box({1, 0, 0}, {1, 1, 1}), BooleanOp::unite, {}, &rep);
  EXPECT_EQ(rep.cells, 2);
  EXPECT_EQ(rep.interior_faces, 1);
  EXPECT_EQ(rep.boundary_faces, 10);
  EXPECT_NEAR(u.volume(), 2, 1e-12);
  EXPECT_EQ(boundary_euler(u), 2);
  EXPECT_EQ(rep.neighbours[0], std::vector<int>{1});
  // Their intersection is a face, no volume: refused, as is any empty result.
  EXPECT_THROW(cad::boolean(box({0, 0, 0}, {1, 1, 1}), box({1, 0, 0}, {1, 1, 1}), BooleanOp::intersect), Error);
}

// Tangent contact: a ball touching a cube in one point. The union keeps both whole; the cube minus the ball
// is the cube.
TEST(Boolean, TangentContact) {
  const VModel b = ball(1);
  const VModel c = box({1, -1, -1}, {2, 2, 2});
  cad::BooleanReport rep;
  const VModel u = cad::boolean(b, c, BooleanOp::unite, {}, &rep);
  EXPECT_EQ(rep.pieces_both, 0);
  EXPECT_NEAR(u.volume(), 4.0 / 3 * pi + 8, 1e-8 * u.volume());
  const VModel d = cad::boolean(c, b, BooleanOp::subtract);
  EXPECT_NEAR(d.volume(), 8, 1e-10);
  EXPECT_EQ(boundary_euler(d), 2);
}

// One operand inside the other: the difference has an inner boundary (two spheres: Euler characteristic 4),
// the union is the outer one, the intersection the inner one.
TEST(Boolean, OneInsideTheOther) {
  const double r = 0.3;
  const VModel c = box({-1, -1, -1}, {2, 2, 2});
  const VModel b = ball(r);
  const double vb = 4.0 / 3 * pi * r * r * r;
  const VModel d = cad::boolean(c, b, BooleanOp::subtract);
  EXPECT_NEAR(d.volume(), 8 - vb, 1e-8 * 8);
  EXPECT_EQ(boundary_euler(d), 4);
  cad::BooleanReport rep;
  const VModel u = cad::boolean(c, b, BooleanOp::unite, {}, &rep);
  EXPECT_NEAR(u.volume(), 8, 1e-8 * 8);
  EXPECT_EQ(boundary_euler(u), 2);
  EXPECT_EQ(rep.pieces_both, 7);
  const VModel i = cad::boolean(c, b, BooleanOp::intersect);
  EXPECT_NEAR(i.volume(), vb, 1e-8 * vb);
}

// Disjoint operands: the union holds both, the intersection is empty (refused with a message).
TEST(Boolean, DisjointOperands) {
  const VModel a = box({0, 0, 0}, {1, 1, 1}), b = box({3, 0, 0}, {1, 2, 1});
  const VModel u = cad::boolean(a, b, BooleanOp::unite);
  EXPECT_EQ(u.num_cells(), 2);
  EXPECT_NEAR(u.volume(), 3, 1e-12);
  EXPECT_EQ(boundary_euler(u), 4);
  try {
    cad::boolean(a, b, BooleanOp::intersect);
    FAIL() << "empty intersection accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("intersection is empty"), std::string::npos) << e.what();
  }
}

// Results as operands, through the JSON file: (cube u cube) minus a cylinder through the middle of their
// shared face (a hole: genus 1), then minus the slab above z = 0.7. A trimmed operand's faces are rebuilt for
// the kernel from their trimming curves; the second fuse's curves then meet within the rebuilt vertices'
// tolerance only (loops 7e-7 apart in space), which the volume integral closes across (without that the
// slab's result was off by 1.5e-10 relative), and the cylinder's intersection edges are solved onto the exact
// surfaces: both volumes hold to rounding.
TEST(Boolean, ResultsAreOperandsAgain) {
  const VModel two = cad::boolean(box({0, 0, 0}, {1, 1, 1}), box({1, 0, 0}, {1, 1, 1}), BooleanOp::unite);
  const VModel back = io::vmodel_from_json(io::to_json(two), "two");
  const double r = 0.3, hole = pi * r * r;
  cad::BooleanReport rep;
  const VModel d = cad::boolean(back, test::glued(make_cylinder({r, 2}), {1, 0.5, -0.5}), BooleanOp::subtract, {}, &rep);
  EXPECT_EQ(rep.cells, 2);
  EXPECT_EQ(rep.neighbours[0], std::vector<int>{1});  // across the holed face (one or more kernel faces)
  EXPECT_NEAR(d.volume(), 2 - hole, 1e-12 * 2);
  EXPECT_EQ(boundary_euler(d), 0);
  const VModel e = cad::boolean(d, box({-1, -1, 0.7}, {4, 3, 1}), BooleanOp::subtract);
  EXPECT_EQ(e.num_cells(), 2);
  EXPECT_NEAR(e.volume(), 0.7 * (2 - hole), 1e-12 * 2);
  EXPECT_EQ(boundary_euler(e), 0);
}

namespace {

// The result cell containing x (by its trim), or -1.
int cell_at(const VModel& m, const std::array<double, 3>& x) {
  for (int c = 0; c < m.num_cells(); ++c)
    if (m.cell(c).contains_param(x)) return c;
  return -1;
}

}  // namespace

// Attribute rules in the overlap of two unit balls (A pure material 0, B pure material 1), checked at points
// whose distances to the two spheres are known: at (0.3, 0, 0) the nearest point of A's sphere is (1, 0, 0),
// 0.7 away and inside B, the nearest of B's is the origin, 0.3 away and inside A.
TEST(Boolean, AttributeRulesInTheOverlap) {
  VModel a = ball(1), b = ball(1, {1, 0, 0});
  // One attribute per rule, so one Boolean checks them all.
  const char* names[] = {"take_a", "take_b", "average", "formula", "distance"};
  cad::BooleanOptions o;
  o.rules["take_a"] = {cad::BlendRule::take_a, ""};
  o.rules["take_b"] = {cad::BlendRule::take_b, ""};
  o.rules["average"] = {cad::BlendRule::average, ""};
  o.rules["formula"] = {cad::BlendRule::formula, "x"};
  o.rules["distance"] = {cad::BlendRule::distance, ""};
  for (const char* n : names) {
    set_constant(a, n, {1, 0});
    set_constant(b, n, {0, 1});
  }
  const VModel u = cad::boolean(a, b, BooleanOp::unite, o);
  const auto at = [&](const char* name, const std::array<double, 3>& x) {
    const int c = cell_at(u, x);
    EXPECT_GE(c, 0);
    std::vector<double> v(2);
    if (c >= 0) u.eval_attribute(c, name, x, v.data());
    return v;
  };
  const std::array<double, 3> p{0.3, 0.02, 0.01}, only_a{-0.5, 0, 0}, only_b{1.5, 0, 0};
  for (const char* n : names) {
    EXPECT_NEAR(at(n, only_a)[0], 1, 1e-12) << n;
    EXPECT_NEAR(at(n, only_b)[1], 1, 1e-12) << n;
  }
  EXPECT_NEAR(at("take_a", p)[0], 1, 1e-12);
  EXPECT_NEAR(at("take_b", p)[1], 1, 1e-12);
  EXPECT_NEAR(at("average", p)[0], 0.5, 1e-12);
  EXPECT_NEAR(at("formula", p)[1], 0.3, 1e-12);
  // The distance blend is fitted as a cubic field on each overlap cell; the weights are about (0.7, 0.3) here.
  const double da = std::hypot(1 - p[0], p[1], p[2]), db = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
  EXPECT_NEAR(at("distance", p)[0], da / (da + db), 0.02);
  // Continuous with B's material at A's sphere inside B, and with A's at B's sphere inside A.
  EXPECT_NEAR(at("distance", {0.97, 0.1, 0})[1], 1, 0.05);
  EXPECT_NEAR(at("distance", {0.03, 0.1, 0})[0], 1, 0.05);
  // Bad rules are refused before any geometry is made.
  cad::BooleanOptions bad;
  bad.default_rule = {cad::BlendRule::formula, "x +"};
  EXPECT_THROW(cad::boolean(a, b, BooleanOp::unite, bad), Error);
}

// Attributes whose component counts differ cannot be blended (but may be taken from one side).
TEST(Boolean, BlendingNeedsEqualComponentCounts) {
  VModel a = box({0, 0, 0}, {1, 1, 1}), b = box({0.5, 0, 0}, {1, 1, 1});
  set_constant(a, "material", {1, 0});
  set_constant(b, "material", {0, 0, 1});
  cad::BooleanOptions avg;
  avg.default_rule = {cad::BlendRule::average, ""};
  EXPECT_THROW(cad::boolean(a, b, BooleanOp::unite, avg), Error);
  EXPECT_NEAR(cad::boolean(a, b, BooleanOp::unite).volume(), 1.5, 1e-12);
}

// The distance blend of two overlapping boxes: at (0.6, 0.5, 0.5) A's face x = 1 (inside B) is 0.4 away and
// B's face x = 0.5 (inside A) 0.1 away, the faces both share farther, so A weighs 0.8.
TEST(Boolean, DistanceBlendOfBoxes) {
  VModel a = box({0, 0, 0}, {1, 1, 1}), b = box({0.5, 0, 0}, {1, 1, 1});
  set_constant(a, "material", {1, 0});
  set_constant(b, "material", {0, 1});
  cad::BooleanOptions o;
  o.default_rule = {cad::BlendRule::distance, ""};
  cad::BooleanReport rep;
  const VModel u = cad::boolean(a, b, BooleanOp::unite, o, &rep);
  EXPECT_EQ(rep.cells, 3);
  EXPECT_EQ(rep.fitted_attributes, 1);
  const std::array<double, 3> p{0.6, 0.5, 0.5};
  const int c = cell_at(u, p);
  ASSERT_GE(c, 0);
  double v[2];
  u.eval_attribute(c, "material", p, v);
  EXPECT_NEAR(v[0], 0.8, 0.02);
  EXPECT_NEAR(v[0] + v[1], 1, 1e-9);
}

// Slicing a blended union: every inside pixel belongs to one cell (the cell whose trim holds its centre; away
// from the cells' shared faces no other cell holds it), its materials are that cell's blended attribute, and
// the inside area per layer is the union's cross-section.
TEST(Boolean, SlicingABlendedUnion) {
  VModel a = ball(1), b = ball(1, {1, 0, 0});
  set_constant(a, "material", {1, 0});
  set_constant(b, "material", {0, 1});
  cad::BooleanOptions o;
  o.default_rule = {cad::BlendRule::formula, "min(1, max(0, x))"};
  const VModel u = cad::boolean(a, b, BooleanOp::unite, o);
  am::SliceOptions so;
  so.layer_thickness = 0.25;
  so.z_range = std::array<double, 2>{-0.3, 0.3};
  so.dpi_x = so.dpi_y = 25.4 / 0.02;
  const std::vector<am::SliceLayer> layers = am::slice_model(u, so);
  const am::SliceGrid g = am::slice_grid(u, so);
  ASSERT_GE(layers.size(), 2u);
  std::int64_t inside = 0, checked = 0, not_one = 0;
  for (const am::SliceLayer& L : layers) {
    std::int64_t in_layer = 0;
    for (int j = 0; j < L.height; ++j)
      for (int i = 0; i < L.width; ++i) {
        const int c = L.owner(i, j);
        if (c < 0) continue;
        ++in_layer;
        const std::array<double, 3> x{g.x(i), g.y(j), L.z};
        if ((i + j) % 7 == 0) {
          int holders = 0;
          for (int k = 0; k < u.num_cells(); ++k) holders += u.cell(k).contains_param(x) ? 1 : 0;
          ++checked;
          not_one += holders != 1;
          EXPECT_TRUE(u.cell(c).contains_param(x) || holders == 0);
        }
        double v[2];
        u.eval_attribute(c, "material", x, v);
        EXPECT_NEAR(L.fractions.pixel(i, j)[0], v[0] / (v[0] + v[1]), 1e-6);
      }
    inside += in_layer;
    // Cross-section of the union of two unit disks of radius rho one apart: 2 pi rho^2 - lens.
    const double rho2 = 1 - L.z * L.z, rho = std::sqrt(rho2);
    const double lens = 2 * rho2 * std::acos(0.5 / rho) - 0.5 * std::sqrt(4 * rho2 - 1);
    const double area = 2 * pi * rho2 - lens;
    EXPECT_NEAR(static_cast<double>(in_layer) * g.dx * g.dy, area, 0.01 * area);
  }
  EXPECT_GT(checked, 1000);
  // Pixel centres on a face between two cells (within the meshes' chordal tolerance) may count twice or never.
  EXPECT_LE(not_one, checked / 500);
}

// Results as operands, with curved trims: the unit ball minus a cylinder of radius 0.4 off the axis, then cut to
// the slab |z| <= h, and the same in the other order. The cylinder lies inside every cross-section of the slab,
// so the volume is the integral of pi (1 - z^2 - r^2) over |z| <= h.
TEST(Boolean, BallMinusCylinderThenSlabInEitherOrder) {
  const double r = 0.4, h = 0.3;
  const VModel b = ball(1);
  const VModel cyl = test::glued(make_cylinder({r, 3}), {0.1, 0.05, -1.5});
  const VModel slab = box({-2, -2, -h}, {4, 4, 2 * h});
  const double exact = pi * (2 * h * (1 - r * r) - 2 * h * h * h / 3);
  const VModel ring_then_slab = cad::boolean(cad::boolean(b, cyl, BooleanOp::subtract), slab, BooleanOp::intersect);
  // 2.5e-8 and 5.1e-8 with the kernel's intersection curves; 6e-14 and 5e-13 with the edges solved onto the
  // surfaces (intersection_edge) and the loops closed across the kernel's gaps.
  EXPECT_NEAR(ring_then_slab.volume(), exact, 1e-10 * exact);
  EXPECT_EQ(boundary_euler(ring_then_slab), 0);
  const VModel slab_then_ring = cad::boolean(cad::boolean(b, slab, BooleanOp::intersect), cyl, BooleanOp::subtract);
  EXPECT_NEAR(slab_then_ring.volume(), exact, 1e-10 * exact);
  EXPECT_EQ(boundary_euler(slab_then_ring), 0);
  std::printf("ball minus cylinder, slab: relative volume errors %.2e (ring first), %.2e (slab first)\n",
              std::abs(ring_then_slab.volume() / exact - 1), std::abs(slab_then_ring.volume() / exact - 1));
}

// A cylinder (radius 0.4, z in [0, 3]) cut below the plane z = 1.5 + x tan 30 degrees (a box turned about the
// y-axis): the plane's odd part in x integrates to zero over the disk, so the volume is pi r^2 1.5. The plane
// cuts the cylinder's rational patches in ellipse arcs, which the kernel approximates; solved onto both
// surfaces, the trimming curves on the plane lie on the cylinder to 1e-10 and the volume holds to 1e-12.
TEST(Boolean, IntersectionEdgesLieOnBothSurfaces) {
  const double r = 0.4, h = 1.5, angle = pi / 6;
  const VModel cyl = test::glued(make_cylinder({r, 3}));
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(-angle, Eigen::Vector3d::UnitY()).toRotationMatrix();
  VModel below;
  for (const TensorSpline<3>& c : make_box({{4, 4, 4}, {-2, -2, -4}}))
    below.add_cell(VCell(transform(c, turn, Eigen::Vector3d(0, 0, h))));
  below.glue();
  const VModel cut = cad::boolean(cyl, below, BooleanOp::intersect);
  const double exact = pi * r * r * h;
  EXPECT_NEAR(cut.volume(), exact, 1e-12 * exact);
  int on_cylinder = 0;
  for (const VCell& c : cut.cells())
    for (const TrimmedFace& f : c.trim()->boundary().faces)
      for (const TrimLoop& l : f.loops)
        for (const TrimCurve& t : l.curves) {
          double worst = 0, tilt = 0;
          const Box<1> d = t.pcurve.domain();
          for (int k = 0; k <= 50; ++k) {
            double uv[2], x[3];
            t.pcurve.eval({d.lo[0] + k / 50.0 * d.extent(0)}, uv);
            f.surface.eval({uv[0], uv[1]}, x);
            worst = std::max(worst, std::abs(std::hypot(x[0], x[1]) - r));
            tilt = std::max(tilt, std::abs(x[2] - h - x[0] * std::tan(angle)));
          }
          // The ellipse arcs: on the cylinder and on the plane.
          if (worst < 1e-6 && tilt < 1e-6) {
            ++on_cylinder;
            EXPECT_LT(worst, 1e-10);
            EXPECT_LT(tilt, 1e-10);
          }
        }
  EXPECT_GE(on_cylinder, 8);  // four arcs, each on the plane face and on the cylinder face
}
