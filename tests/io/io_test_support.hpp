#pragma once
// Support for the io tests: a temporary directory per test, random object lists and exact comparison.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "support/spline_fixtures.hpp"
#include "trivar/spline/any_spline.hpp"

namespace trivar::test {

// A fresh directory per test (tests may run in parallel), removed with everything in it at the end.
class TempDir {
public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() / ("trivar_io_" + std::string(info->test_suite_name()) + "_" +
                                                     info->name() + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  std::string file(const std::string& name) const { return (dir_ / name).string(); }
  // Number of entries in the directory: a failed write must leave none behind.
  int entries() const {
    int n = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir_)) ++n;
    return n;
  }

private:
  std::filesystem::path dir_;
};

// Curves, surfaces and volumes of several degrees and control dimensions, clamped and unclamped.
inline std::vector<AnySpline> random_objects(bool rational, unsigned seed) {
  std::vector<AnySpline> out;
  for (int dim : {1, 2, 3, 5}) {
    out.emplace_back(random_spline<1>({1 + dim % 4}, {5}, dim, rational, seed++));
    out.emplace_back(random_spline<2>({2, 3}, {3, 4}, dim, rational, seed++, dim != 2));
    out.emplace_back(random_spline<3>({1, 2, 3}, {2, 3, 2}, dim, rational, seed++, dim != 3));
  }
  return out;
}

// Same type, knots, control dimension and homogeneous coefficients, compared with == (bit for bit; -0.0
// and 0.0 are told apart by the sign bit).
inline void expect_identical(const AnySpline& a, const AnySpline& b) {
  ASSERT_EQ(a.index(), b.index());
  std::visit(
      [&](const auto& x) {
        const auto& y = std::get<std::decay_t<decltype(x)>>(b);
        EXPECT_EQ(x.dim(), y.dim());
        EXPECT_EQ(x.is_rational(), y.is_rational());
        EXPECT_TRUE(x.knot_vectors() == y.knot_vectors());
        ASSERT_EQ(x.coefs().size(), y.coefs().size());
        for (std::size_t i = 0; i < x.coefs().size(); ++i) {
          EXPECT_EQ(x.coefs()[i], y.coefs()[i]) << "coefficient value " << i;
          EXPECT_EQ(std::signbit(x.coefs()[i]), std::signbit(y.coefs()[i])) << "coefficient value " << i;
        }
      },
      a);
}

}  // namespace trivar::test
