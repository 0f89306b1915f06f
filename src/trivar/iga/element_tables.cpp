#include "trivar/iga/element_tables.hpp"

#include "trivar/core/gauss_legendre.hpp"
#include "trivar/spline/basis.hpp"

namespace trivar {

DirectionTable direction_table(const KnotVector& kv, int points) {
  const QuadratureRule rule = gauss_legendre(points);
  const std::vector<double> bp = kv.breakpoints();
  DirectionTable t;
  t.degree = kv.degree();
  t.points = points;
  const int n = t.functions();
  double N[kMaxDegree + 1], dN[kMaxDegree + 1];
  for (std::size_t e = 0; e + 1 < bp.size(); ++e) {
    const double a = bp[e], b = bp[e + 1];
    const int span = kv.find_span(0.5 * (a + b));
    t.first.push_back(span - t.degree);
    t.lo.push_back(a);
    t.hi.push_back(b);
    const std::size_t base = t.val.size();
    t.val.resize(base + static_cast<std::size_t>(n * points));
    t.der.resize(base + static_cast<std::size_t>(n * points));
    for (int q = 0; q < points; ++q) {
      const double u = a + (b - a) * rule.nodes[static_cast<std::size_t>(q)];
      t.u.push_back(u);
      t.weight.push_back((b - a) * rule.weights[static_cast<std::size_t>(q)]);
      basis_values_first_derivatives(kv, span, u, N, dN);
      for (int i = 0; i < n; ++i) {
        t.val[base + static_cast<std::size_t>(i * points + q)] = N[i];
        t.der[base + static_cast<std::size_t>(i * points + q)] = dN[i];
      }
    }
  }
  return t;
}

}  // namespace trivar
