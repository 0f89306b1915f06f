#include "trivar/model/attribute.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "trivar/core/error.hpp"
#include "trivar/model/block.hpp"
#include "trivar/model/vcell.hpp"
#include "trivar/spline/affine_transform.hpp"

using namespace trivar;

namespace {

// A rotated, shifted, stretched cell: x = R diag(2, 1, 3) u + b, so x(u) is known in closed form.
const Eigen::Matrix3d kR = (Eigen::Matrix3d() << 0, -1, 0, 1, 0, 0, 0, 0, 1).finished();
const Eigen::Vector3d kB(1, 2, 3);

VCell rotated_cell() {
  return VCell(transform(make_block<3>({2, 1, 1}, {2, 1, 3}, {2, 1, 3}), kR, kB));
}

}  // namespace

TEST(Attribute, ConstantFieldAndExpressionsEvaluateAtCellParameters) {
  VCell cell = rotated_cell();
  cell.set_attribute("color", Attribute::constant({0.1, 0.2, 0.3}));
  // Field on [0, 2] x [0, 1] x [-1, 1], linear: f = (s0, s1 + s2); mapped affinely onto the cell domain [0,1]^3.
  const KnotVector k0 = KnotVector::open_uniform(1, 1, 0, 2), k1 = KnotVector::open_uniform(1, 1, 0, 1),
                   k2 = KnotVector::open_uniform(1, 1, -1, 1);
  std::vector<double> c;
  for (double s2 : {-1.0, 1.0})
    for (double s1 : {0.0, 1.0})
      for (double s0 : {0.0, 2.0}) c.insert(c.end(), {s0, s1 + s2});
  cell.set_attribute("field", Attribute::field(TensorSpline<3>::from_cartesian({k0, k1, k2}, 2, c)));
  cell.set_attribute("model", Attribute::expression({"x + 10*y", "z^2"}, Attribute::Space::model));
  cell.set_attribute("param", Attribute::expression({"u*v*w"}, Attribute::Space::parametric));
  for (const Param<3>& u : {Param<3>{0.2, 0.7, 0.4}, Param<3>{1, 0, 0.5}, Param<3>{0.9, 0.1, 0.95}}) {
    double out[3];
    cell.eval_attribute("color", u, out);
    EXPECT_EQ(out[2], 0.3);
    cell.eval_attribute("field", u, out);
    EXPECT_NEAR(out[0], 2 * u[0], 1e-15);
    EXPECT_NEAR(out[1], u[1] + (2 * u[2] - 1), 1e-15);
    const Eigen::Vector3d x = kR * Eigen::Vector3d(2 * u[0], u[1], 3 * u[2]) + kB;
    cell.eval_attribute("model", u, out);
    EXPECT_NEAR(out[0], x.x() + 10 * x.y(), 1e-13);
    EXPECT_NEAR(out[1], x.z() * x.z(), 1e-13);
    cell.eval_attribute("param", u, out);
    EXPECT_NEAR(out[0], u[0] * u[1] * u[2], 1e-15);
  }
  EXPECT_EQ(cell.attribute("model").components(), 2);
  EXPECT_EQ(cell.attribute("field").components(), 2);
  EXPECT_EQ(cell.attribute("param").kind(), Attribute::Kind::expression);
}

TEST(Attribute, InvalidAttributesFailCleanly) {
  EXPECT_THROW(Attribute::constant({}), Error);
  EXPECT_THROW(Attribute::constant({NAN}), Error);
  EXPECT_THROW(Attribute::expression({}, Attribute::Space::model), Error);
  EXPECT_THROW(Attribute::expression({"u + 1"}, Attribute::Space::model), Error);  // u is not a model variable
  EXPECT_THROW(Attribute::expression({"x", "y +"}, Attribute::Space::model), Error);
  EXPECT_THROW(Attribute::field(TensorSpline<3>()), Error);
  const VCell cell = rotated_cell();
  try {
    cell.attribute("density");
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "V-cell: no attribute 'density'");
  }
}

TEST(Attribute, ManyParametersGiveTheSameValuesAsOneAtATime) {
  const VCell cell = rotated_cell();
  const TensorSpline<3>& g = cell.geometry();
  const std::vector<Attribute> attributes = {
      Attribute::constant({0.25, 0.75}),
      Attribute::field(make_block<3>({2, 1, 1}, {1, 1, 1}, {1, 2, 3})),
      Attribute::expression({"x + 10*y", "sqrt(z) - x*y"}, Attribute::Space::model),
      Attribute::expression({"u*v*w", "min(u, v) + 1"}, Attribute::Space::parametric)};
  // Parameters in the domain and, clamped onto it, outside (there the given model points are not used).
  std::vector<Param<3>> u;
  for (int i = 0; i < 300; ++i)
    u.push_back({std::fmod(0.37 * i, 1.3) - 0.1, std::fmod(0.61 * i, 1.0), std::fmod(0.13 * i, 1.0)});
  std::vector<double> points;
  for (const auto& p : u) {
    double x[3] = {-1, -1, -1};  // wrong on purpose outside the domain
    if (p[0] >= 0 && p[0] <= 1) g.eval(p, x);
    points.insert(points.end(), x, x + 3);
  }
  for (const Attribute& a : attributes) {
    const auto m = static_cast<std::size_t>(a.components());
    std::vector<double> many(m * u.size());
    a.eval_many(g, u, points.data(), many.data());
    for (std::size_t i = 0; i < u.size(); ++i) {
      double one[3], at[3];
      a.eval(g, u[i], one);
      if (u[i][0] >= 0 && u[i][0] <= 1) a.eval_at(g, u[i], points.data() + 3 * i, at);
      else std::copy(one, one + 3, at);
      for (std::size_t c = 0; c < m; ++c) {
        EXPECT_EQ(many[m * i + c], one[c]) << "attribute " << &a - attributes.data() << " point " << i;
        EXPECT_EQ(at[c], one[c]);
      }
    }
  }
  // Model points given directly (the slicer's path): the values at the parameters inside the domain.
  const Attribute& model = attributes[2];
  std::vector<double> inside_points, from_points;
  std::vector<Param<3>> inside;
  for (std::size_t i = 0; i < u.size(); ++i)
    if (u[i][0] >= 0 && u[i][0] <= 1) {
      inside.push_back(u[i]);
      inside_points.insert(inside_points.end(), points.begin() + 3 * i, points.begin() + 3 * i + 3);
    }
  from_points.resize(2 * inside.size());
  model.eval_model_points(inside_points, from_points.data());
  for (std::size_t i = 0; i < inside.size(); ++i) {
    double one[2];
    model.eval(g, inside[i], one);
    EXPECT_EQ(from_points[2 * i], one[0]) << i;
    EXPECT_EQ(from_points[2 * i + 1], one[1]) << i;
  }
  double ignored[2];
  for (const std::size_t k : {std::size_t{0}, std::size_t{1}, std::size_t{3}})
    EXPECT_THROW(attributes[k].eval_model_points(std::span<const double>(inside_points.data(), 3), ignored), Error)
        << "attribute " << k << " is no model-space expression";
}
