#include "trivar/spline/knot_refinement.hpp"

#include <algorithm>

#include "trivar/core/error.hpp"
#include "trivar/core/number_format.hpp"

namespace trivar {

void express_in(std::span<const double> local, int p, const KnotVector& to, int& first, std::vector<double>& coefs) {
  require(static_cast<int>(local.size()) == p + 2 && p >= 0 && p <= kMaxDegree,
          "knot refinement: " + std::to_string(local.size()) + " local knots for degree " + std::to_string(p));
  const double a = local.front(), b = local.back();
  const auto& t = to.knots();
  const int m_start = static_cast<int>(std::upper_bound(local.begin(), local.end(), a) - local.begin());
  const int m_end = static_cast<int>(local.end() - std::lower_bound(local.begin(), local.end(), b));
  const auto lo = std::upper_bound(t.begin(), t.end(), a);  // first knot of `to` strictly inside (a, b)
  const auto hi = std::lower_bound(t.begin(), t.end(), b);
  require(lo - t.begin() >= m_start && *(lo - m_start) == a && t.end() - hi >= m_end && *(hi + (m_end - 1)) == b,
          "knot refinement: target knot vector does not contain the support ends " + format_number(a) + ", " + format_number(b));
  // Every interior knot of `local` must be in `to` at least as often.
  auto li = local.begin() + m_start;
  const auto le = local.end() - m_end;
  for (auto ti = lo; ti != hi && li != le; ++ti)
    if (*li == *ti) ++li;
    else require(*li > *ti, "knot refinement: target knot vector lacks knot " + format_number(*li));
  require(li == le, "knot refinement: target knot vector lacks knot " + (li == le ? std::string() : format_number(*li)));
  // The part of `to` from local's first knot to its last, with local's end multiplicities: an exact split.
  first = static_cast<int>(lo - t.begin()) - m_start;
  const auto fine = std::span<const double>(t).subspan(static_cast<std::size_t>(first),
                                                          static_cast<std::size_t>(hi - lo + m_start + m_end));
  coefs.resize(fine.size() - static_cast<std::size_t>(p) - 1);
  express_in<double>(local, fine, coefs.data());
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
