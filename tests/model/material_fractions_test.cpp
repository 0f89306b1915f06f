#include "trivar/model/material_fractions.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "trivar/core/error.hpp"
#include "trivar/model/block.hpp"

using namespace trivar;

namespace {

std::string rule_error(const std::vector<double>& f) {
  try {
    material_fraction_sum(f, [] { return std::string("here"); });
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

const std::string kRule = "; fractions must be finite and >= 0 with a positive sum";

}  // namespace

TEST(MaterialFractions, TheRuleNamesTheFirstBadFraction) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(rule_error({nan, 1}), "here: material fractions (NaN, 1): fraction 0 is not finite" + kRule);
  EXPECT_EQ(rule_error({1, inf}), "here: material fractions (1, inf): fraction 1 is not finite" + kRule);
  EXPECT_EQ(rule_error({0.5, -0.25}), "here: material fractions (0.5, -0.25): fraction 1 is negative" + kRule);
  EXPECT_EQ(rule_error({0, 0, 0}), "here: material fractions (0, 0, 0): sum to 0" + kRule);
  EXPECT_EQ(rule_error({1e308, 1e308}), "here: material fractions (1e+308, 1e+308): sum to a value that is not finite" + kRule);
  // Proportions: the sum is what consumers divide by.
  EXPECT_EQ(material_fraction_sum(std::vector<double>{2, 1, 0}, [] { return std::string(); }), 3.0);
}

// The model check samples the corners, so a field negative only at one corner is found, at that corner.
TEST(MaterialFractions, ModelCheckFindsTheCornerWhereAFormulaTurnsNegative) {
  VModel m;
  m.add_cell(VCell(make_block<3>({1, 1, 1}, {1, 1, 1}, {1, 1, 1})));
  m.add_cell(VCell(make_block<3>({1, 1, 1}, {1, 1, 1}, {1, 1, 1})));
  m.cell(0).set_attribute("material", Attribute::constant({1, 0}));
  m.cell(1).set_attribute("material", Attribute::expression({"1 - u*v*w", "u"}, Attribute::Space::parametric));
  EXPECT_NO_THROW(check_material_fractions(m));
  m.cell(1).set_attribute("material", Attribute::expression({"1 - 2*u*v*w", "0"}, Attribute::Space::parametric));
  try {
    check_material_fractions(m);
    FAIL() << "expected trivar::Error";
  } catch (const Error& e) {
    // 1 - 2uvw < 0 near (1, 1, 1); on the 3 x 3 x 3 grid (u fastest) 1 - 2*1*1*0.5 = 0 at (1, 1, 0.5) comes first.
    EXPECT_EQ(std::string(e.what()),
              "cell 1 at parameter (1, 1, 0.5): material fractions (0, 0): sum to 0" + kRule);
  }
  EXPECT_NO_THROW(check_material_fractions(m, "density"));  // no cell has it
}
