#include "trivar/lr/exact_rank.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include <gmpxx.h>

using namespace trivar;

// Doubles are dyadic rationals; ModP(x) is their exact residue, so field identities of the rationals hold.
TEST(ExactRank, ModPIsTheResidueOfTheDyadicRational) {
  EXPECT_EQ(ModP(0.5) * ModP(2), ModP(1));
  EXPECT_EQ(ModP(-3.25) + ModP(3.25), ModP(0));
  EXPECT_EQ(ModP(std::ldexp(1.0, -1000)) * ModP(std::ldexp(1.0, 1000)), ModP(1));
  EXPECT_EQ(ModP(0.75) / ModP(3), ModP(0.25));
  EXPECT_EQ(ModP(1.0) / ModP(3) * ModP(3), ModP(1));  // 1/3 exists modulo p
  EXPECT_EQ(ModP(-1).value(), ModP::kP - 1);
  EXPECT_EQ(ModP(std::ldexp(1.0, 61)), ModP(1));  // 2^61 = 1 modulo 2^61 - 1
  EXPECT_THROW(ModP(1) / ModP(0), UnluckyPrime);
}

// Known ranks, by hand: rows (1 2 3), (2 4 6), (1 0 1) have rank 2; a permuted identity with one row repeated
// has rank 3; the Hilbert matrix of order 6 (ill-conditioned, condition number ~1.5e7) is non-singular.
TEST(ExactRank, EchelonRankOfKnownMatrices) {
  const auto row = [](std::initializer_list<int> v) {
    SparseRow<mpq_class> r;
    int c = 0;
    for (int x : v) {
      if (x != 0) r.emplace_back(c, mpq_class(x));
      ++c;
    }
    return r;
  };
  EXPECT_EQ(echelon_rank<mpq_class>({row({1, 2, 3}), row({2, 4, 6}), row({1, 0, 1})}, 3), 2);
  EXPECT_EQ(echelon_rank<mpq_class>({row({0, 0, 1}), row({1, 0, 0}), row({0, 1, 0}), row({1, 0, 0})}, 3), 3);
  std::vector<SparseRow<mpq_class>> hq;
  std::vector<SparseRow<ModP>> hp;
  for (int i = 0; i < 6; ++i) {
    hq.emplace_back();
    hp.emplace_back();
    for (int j = 0; j < 6; ++j) {
      hq.back().emplace_back(j, mpq_class(1, i + j + 1));
      hp.back().emplace_back(j, ModP(1) / ModP(i + j + 1));
    }
  }
  EXPECT_EQ(echelon_rank<mpq_class>(hq, 6), 6);
  EXPECT_EQ(echelon_rank<ModP>(hp, 6), 6);
  // The first five rows and their sum: rank 5 in both fields.
  hq.back().clear();
  hp.back().clear();
  for (int j = 0; j < 6; ++j) {
    mpq_class s = 0;
    ModP t(0);
    for (int i = 0; i < 5; ++i) {
      s += mpq_class(1, i + j + 1);
      t = t + ModP(1) / ModP(i + j + 1);
    }
    hq.back().emplace_back(j, s);
    hp.back().emplace_back(j, t);
  }
  EXPECT_EQ(echelon_rank<mpq_class>(hq, 6), 5);
  EXPECT_EQ(echelon_rank<ModP>(hp, 6), 5);
}
