// Booleans of V-models: volumes against closed forms, the robustness cases (coincident faces, tangent contact,
// one operand inside the other, disjoint operands, results as operands), the topology of the result and the
// attribute blends.
#include <gtest/gtest.h>

#include <Eigen/Core>

#include "trivar/cad/boolean.hpp"
#include "trivar/io/vmodel_json.hpp"
#include "trivar/model/ball.hpp"
#include "trivar/model/cylinder.hpp"
#include "trivar/model/primitives.hpp"
#include "trivar/model/torus.hpp"
#include "trivar/model/trimmed_tessellation.hpp"
#include "trivar/spline/affine_transform.hpp"

using namespace trivar;
using cad::BooleanOp;

namespace {

const double kPi = 3.14159265358979323846;

VModel model_of(const CellComplex& cells, const Eigen::Vector3d& shift = Eigen::Vector3d::Zero()) {
  VModel m;
  for (const SplineVolume& c : cells) m.add_cell(VCell(transform(c, Eigen::Matrix3d::Identity(), shift)));
  m.glue();
  return m;
}

VModel box(const Eigen::Vector3d& lo, const Eigen::Vector3d& size) { return model_of(make_box({size, lo})); }

VModel ball(double r, const Eigen::Vector3d& c = Eigen::Vector3d::Zero()) { return model_of(make_ball({r, c})); }

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
  const VModel cyl = model_of(make_cylinder({r, 3}), {0, 0, -1.5});
  cad::BooleanReport rep;
  const VModel ring = cad::boolean(b, cyl, BooleanOp::subtract, {}, &rep);
  const double exact = 4.0 / 3 * kPi * std::pow(R * R - r * r, 1.5);
  EXPECT_NEAR(ring.volume(), exact, 1e-8 * exact);
  EXPECT_EQ(rep.cells_a, 7);
  EXPECT_EQ(rep.cells, rep.pieces_a_only);
  EXPECT_EQ(boundary_euler(ring), 0);  // a torus-like surface: genus 1
  expect_symmetric_neighbours(rep);
}
