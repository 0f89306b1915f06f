// Fields fitted from samples at model points and attached to a curved V-cell: a field that lies in the fit's
// space is reproduced everywhere in the cell (not only at the samples: the point inversion, the fit on the cell's
// parameter box and the tensor expansion are all exact), samples outside the cell are skipped, and material
// fractions with a sharp transition stay >= 0 everywhere while meeting the tolerance at the samples.
#include "trivar/fit/cell_field.hpp"

#include <gtest/gtest.h>

#include <random>

#include "trivar/model/material_fractions.hpp"
#include "trivar/model/vmodel.hpp"
#include "trivar/spline/knot_vector.hpp"

namespace trivar::cell_field_test {
namespace {

// A curved hexahedron: [0, 1]^3 bent (x = u + 0.2 v^2, y = v + 0.1 u w, z = w), triquadratic.
TensorSpline<3> bent_block() {
  std::array<KnotVector, 3> k = {KnotVector::open_uniform(2, 2), KnotVector::open_uniform(2, 2), KnotVector::open_uniform(2, 2)};
  std::array<std::vector<double>, 3> g = {k[0].greville(), k[1].greville(), k[2].greville()};
  // The maps are quadratic, so their coefficients follow from the polar forms; least squares on a grid is exact.
  std::vector<double> coefs;
  const std::size_t n = g[0].size();
  for (std::size_t c = 0; c < n; ++c)
    for (std::size_t b = 0; b < n; ++b)
      for (std::size_t a = 0; a < n; ++a) {
        // Greville points of a degree-2 open uniform vector with 2 elements: 0, 1/4, 3/4, 1. The control point of
        // u + 0.2 v^2 is u* + 0.2 * blossom(v), blossom of v^2 at the B-spline's two interior knots.
        const auto blossom = [&](std::size_t i) {
          const auto& t = k[1].knots();
          return t[i + 1] * t[i + 2];
        };
        const auto blossom_w = [&](std::size_t i) { return g[2][i]; };
        coefs.push_back(g[0][a] + 0.2 * blossom(b));
        coefs.push_back(g[1][b] + 0.1 * g[0][a] * blossom_w(c));
        coefs.push_back(g[2][c]);
      }
  return TensorSpline<3>(k, 3, false, std::move(coefs));
}

TEST(CellField, AFieldInTheSpaceIsReproducedThroughoutTheCell) {
  const VCell cell(bent_block());
  // Check the construction against the closed form first.
  double x[3];
  cell.geometry().eval({0.3, 0.7, 0.6}, x);
  ASSERT_NEAR(x[0], 0.3 + 0.2 * 0.49, 1e-14);
  ASSERT_NEAR(x[1], 0.7 + 0.1 * 0.3 * 0.6, 1e-14);
  const auto f = [](const Param<3>& u, double* v) {  // two components, quadratic in the parameters
    v[0] = 0.2 + 0.5 * u[0] * u[1] - 0.3 * u[2] * u[2];
    v[1] = 1.0 - u[0] + 0.25 * u[1] * u[2];
  };
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> r(0.0, 1.0);
  ScatteredData<3> samples;
  samples.dim = 2;
  for (int i = 0; i < 1500; ++i) {
    const Param<3> u{r(rng), r(rng), r(rng)};
    double p[3], v[2];
    cell.geometry().eval(u, p);
    f(u, v);
    samples.params.push_back({p[0], p[1], p[2]});
    samples.values.insert(samples.values.end(), v, v + 2);
  }
  for (int i = 0; i < 50; ++i) {  // outside the cell: beyond x = 1.2 or below y = 0
    samples.params.push_back({1.5 + r(rng), r(rng), r(rng)});
    samples.params.push_back({r(rng), -0.5 - r(rng), r(rng)});
    samples.values.insert(samples.values.end(), {9.0, 9.0, 9.0, 9.0});
  }
  CellFieldOptions o;
  o.fit.tolerance = 1e-9;
  o.fit.initial_elements = 2;
  o.fit.smoothing = 0.0;
  const CellField c = fit_cell_field(cell, samples, o);
  EXPECT_EQ(c.used, 1500u);
  EXPECT_EQ(c.outside, 100u);
  EXPECT_TRUE(c.fit.converged);
  EXPECT_LT(c.max_error, 1e-10);
  VCell attached = cell;
  attached.set_attribute("field", c.attribute);
  for (int i = 0; i < 200; ++i) {
    const Param<3> u{r(rng), r(rng), r(rng)};
    double got[2], want[2];
    attached.eval_attribute("field", u, got);
    f(u, want);
    EXPECT_NEAR(got[0], want[0], 1e-9);
    EXPECT_NEAR(got[1], want[1], 1e-9);
  }
}

TEST(CellField, MaterialFractionsStayNonNegativeEverywhere) {
  const VCell cell(bent_block());
  // Two materials switching across the plane x = 0.6 (a logistic of width 0.08 in model coordinates).
  const auto fraction = [](double px) { return 1.0 / (1.0 + std::exp(-(px - 0.6) / 0.08)); };
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> r(0.0, 1.0);
  ScatteredData<3> samples;
  samples.dim = 2;
  for (int i = 0; i < 3000; ++i) {
    const Param<3> u{r(rng), r(rng), r(rng)};
    double p[3];
    cell.geometry().eval(u, p);
    samples.params.push_back({p[0], p[1], p[2]});
    samples.values.push_back(1.0 - fraction(p[0]));
    samples.values.push_back(fraction(p[0]));
  }
  CellFieldOptions o;
  o.fit.tolerance = 0.02;
  o.fit.smoothing = 1e-6;
  o.fit.initial_elements = 2;
  o.fit.max_levels = 6;
  o.fractions = true;
  const CellField c = fit_cell_field(cell, samples, o);
  EXPECT_TRUE(c.fit.converged) << c.fit.stop_reason;
  EXPECT_LE(c.max_error, o.fit.tolerance);  // after clamping too (the raised coefficients are where samples are few)
  std::printf("fractions: %d coefficients, largest clamp %.3g, error at the samples %.3g\n", c.fit.spline.num_basis(),
              c.clamped, c.max_error);
  VModel model;
  VCell attached = cell;
  attached.set_attribute("material", c.attribute);
  model.add_cell(std::move(attached));
  // The rule every consumer applies on its check grid, and the field on a finer grid of the whole cell.
  EXPECT_NO_THROW(check_material_fractions(model));
  for (int i = 0; i <= 20; ++i)
    for (int j = 0; j <= 20; ++j)
      for (int k = 0; k <= 4; ++k) {
        double v[2];
        model.cell(0).eval_attribute("material", {i / 20.0, j / 20.0, k / 4.0}, v);
        EXPECT_GE(v[0], 0.0);
        EXPECT_GE(v[1], 0.0);
        EXPECT_NEAR(v[0] + v[1], 1.0, 1e-10);
      }
}

TEST(CellField, TooFewSamplesInTheCell) {
  const VCell cell(bent_block());
  ScatteredData<3> samples;
  for (int i = 0; i < 20; ++i) {
    samples.params.push_back({3.0 + i, 2.0 + 0.5 * i * i, 1.0 + i % 3});
    samples.values.push_back(1.0);
  }
  CellFieldOptions o;
  o.fit.tolerance = 0.1;
  try {
    fit_cell_field(cell, samples, o);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("0 of 20 samples lie in the cell"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace trivar::cell_field_test
