#pragma once
// Exact rank of sparse matrices over a field: the integers modulo the prime 2^61 - 1 (ModP), or the rationals
// (any field type with + - * / and comparison with 0, such as GMP's mpq_class).
//
// Why modulo a prime: the entries of interest are rational (rational functions of dyadic-rational knots). The
// reduction modulo p of rationals whose denominators p does not divide is a ring homomorphism, so every minor
// reduces to the reduced minor, and the rank modulo p is at most the rank over Q. Full rank modulo p therefore
// proves full rank over Q; a deficiency modulo p must be confirmed in rational arithmetic (it is rare that p
// divides a numerator by accident, but possible). A division by a value that is 0 modulo p but not over Q
// (p divides its numerator) throws UnluckyPrime.
#include <cstdint>
#include <utility>
#include <vector>

namespace trivar {

struct UnluckyPrime {};

__extension__ typedef unsigned __int128 UInt128;  // GCC / Clang extension (products of residues)

// An integer modulo p = 2^61 - 1 (a Mersenne prime: reduction by shift and add).
class ModP {
public:
  static constexpr std::uint64_t kP = (std::uint64_t{1} << 61) - 1;

  ModP() = default;
  explicit ModP(int v) : v_(v >= 0 ? std::uint64_t(v) % kP : kP - std::uint64_t(-std::int64_t{v}) % kP) {}
  // The exact value of x (a dyadic rational m 2^e) modulo p; 2^61 = 1 modulo p, so 2^e = 2^(e mod 61).
  explicit ModP(double x);

  friend ModP operator+(ModP a, ModP b) { return from(a.v_ + b.v_ >= kP ? a.v_ + b.v_ - kP : a.v_ + b.v_); }
  friend ModP operator-(ModP a, ModP b) { return from(a.v_ >= b.v_ ? a.v_ - b.v_ : a.v_ + kP - b.v_); }
  friend ModP operator*(ModP a, ModP b) { return from(reduce(static_cast<UInt128>(a.v_) * b.v_)); }
  // Throws UnluckyPrime on b = 0 (callers divide only by values that are non-zero over Q).
  friend ModP operator/(ModP a, ModP b) { return a * b.inverse(); }
  friend bool operator==(ModP a, ModP b) { return a.v_ == b.v_; }
  std::uint64_t value() const { return v_; }

private:
  std::uint64_t v_ = 0;

  static ModP from(std::uint64_t v) {
    ModP r;
    r.v_ = v;
    return r;
  }
  static std::uint64_t reduce(UInt128 x) {
    std::uint64_t r = static_cast<std::uint64_t>(x & kP) + static_cast<std::uint64_t>(x >> 61);
    while (r >= kP) r -= kP;
    return r;
  }
  ModP inverse() const;
};

// A sparse row: (column, value) pairs, columns ascending, no zero values.
template <class F>
using SparseRow = std::vector<std::pair<int, F>>;

// Rank of the rows (Gaussian elimination to echelon form, one row at a time against the pivot rows so far;
// a pivot row is scaled to leading value 1). cols bounds the column indices.
template <class F>
int echelon_rank(std::vector<SparseRow<F>> rows, int cols) {
  const F zero(0);
  std::vector<int> pivot_of(static_cast<std::size_t>(cols), -1);
  std::vector<SparseRow<F>> pivots;
  SparseRow<F> next;
  for (auto& row : rows) {
    while (!row.empty()) {
      const int lead = row.front().first;
      const int pv = pivot_of[static_cast<std::size_t>(lead)];
      if (pv < 0) {
        const F inv = F(1) / row.front().second;
        for (auto& [c, v] : row) v = v * inv;
        pivot_of[static_cast<std::size_t>(lead)] = static_cast<int>(pivots.size());
        pivots.push_back(std::move(row));
        break;
      }
      // row -= row.lead * pivot, merging the two sorted rows; the leading entry cancels.
      const F f = row.front().second;
      const auto& pr = pivots[static_cast<std::size_t>(pv)];
      next.clear();
      std::size_t i = 1, j = 1;
      while (i < row.size() || j < pr.size()) {
        if (j == pr.size() || (i < row.size() && row[i].first < pr[j].first)) {
          next.push_back(std::move(row[i++]));
        } else if (i == row.size() || pr[j].first < row[i].first) {
          next.emplace_back(pr[j].first, zero - f * pr[j].second);
          ++j;
        } else {
          F v = row[i].second - f * pr[j].second;
          if (!(v == zero)) next.emplace_back(row[i].first, std::move(v));
          ++i;
          ++j;
        }
      }
      std::swap(row, next);
    }
  }
  return static_cast<int>(pivots.size());
}

}  // namespace trivar
