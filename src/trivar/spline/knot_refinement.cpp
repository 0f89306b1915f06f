#include "trivar/spline/knot_refinement.hpp"

#include <algorithm>

#include "trivar/core/error.hpp"
#include "trivar/core/number_format.hpp"

namespace trivar {

namespace {

// Boehm's rule on the local knot vector K (coefficients c of the B-splines on K): insert z, K[0] < z < K.back().
void boehm_insert(std::vector<double>& K, std::vector<double>& c, int p, double z) {
  const int n = static_cast<int>(K.size()) - p - 1;  // B-splines on K
  const int k = static_cast<int>(std::upper_bound(K.begin(), K.end(), z) - K.begin()) - 1;  // K[k] <= z < K[k+1]
  std::vector<double> q(n + 1);
  for (int j = 0; j <= n; ++j) {
    const double prev = j - 1 >= 0 && j - 1 < n ? c[j - 1] : 0.0;
    const double cur = j < n ? c[j] : 0.0;
    if (j <= k - p) {
      q[j] = cur;
    } else if (j >= k + 1) {
      q[j] = prev;
    } else {
      const double alpha = (z - K[j]) / (K[j + p] - K[j]);
      q[j] = alpha * cur + (1.0 - alpha) * prev;
    }
  }
  K.insert(K.begin() + k + 1, z);
  c.swap(q);
}

}  // namespace

void express_in(std::span<const double> local, int p, const KnotVector& to, int& first, std::vector<double>& coefs) {
  const double a = local.front(), b = local.back();
  const auto& t = to.knots();
  const int m_start = static_cast<int>(std::upper_bound(local.begin(), local.end(), a) - local.begin());
  const int m_end = static_cast<int>(local.end() - std::lower_bound(local.begin(), local.end(), b));
  const auto lo = std::upper_bound(t.begin(), t.end(), a);  // first knot of `to` strictly inside (a, b)
  const auto hi = std::lower_bound(t.begin(), t.end(), b);
  require(lo - t.begin() >= m_start && *(lo - m_start) == a && t.end() - hi >= m_end && *(hi + (m_end - 1)) == b,
          "knot refinement: target knot vector does not contain the support ends " + format_number(a) + ", " + format_number(b));
  first = static_cast<int>(lo - t.begin()) - m_start;

  std::vector<double> K(local.begin(), local.end());
  coefs.assign(1, 1.0);
  // Merge the interior knots of `to` against those of `local`; each one `local` lacks is inserted.
  auto li = local.begin() + m_start;
  const auto le = local.end() - m_end;
  for (auto ti = lo; ti != hi; ++ti) {
    if (li != le && *li == *ti) {
      ++li;
      continue;
    }
    require(li == le || *li > *ti, "knot refinement: target knot vector lacks knot " + format_number(*li));
    boehm_insert(K, coefs, p, *ti);
  }
  require(li == le, "knot refinement: target knot vector lacks knot " + (li == le ? std::string() : format_number(*li)));
}

SparseRowMatrix refinement_matrix(const KnotVector& from, const KnotVector& to) {
  const int p = from.degree();
  require(to.degree() == p, "knot refinement: degrees differ (" + std::to_string(p) + " and " +
                                std::to_string(to.degree()) + ")");
  std::vector<Eigen::Triplet<double>> entries;
  std::vector<double> c;
  int first = 0;
  for (int i = 0; i < from.size(); ++i) {
    express_in(std::span<const double>(from.data() + i, p + 2), p, to, first, c);
    for (int j = 0; j < static_cast<int>(c.size()); ++j)
      if (c[j] != 0.0) entries.emplace_back(first + j, i, c[j]);
  }
  SparseRowMatrix R(to.size(), from.size());
  R.setFromTriplets(entries.begin(), entries.end());
  return R;
}

KnotVector with_knots(const KnotVector& kv, std::span<const double> knots) {
  std::vector<double> t = kv.knots();
  for (double z : knots) {
    require(z >= kv.start() && z <= kv.end(), "knot insertion: knot " + format_number(z) + " is outside the domain [" +
                                                  format_number(kv.start()) + ", " + format_number(kv.end()) + "]");
    t.insert(std::upper_bound(t.begin(), t.end(), z), z);
  }
  return KnotVector(kv.degree(), std::move(t));
}

}  // namespace trivar
