#include "trivar/tspline/t_spline_tessellation.hpp"

#include <algorithm>
#include <cmath>

#include "trivar/core/clamped_count.hpp"
#include "trivar/core/error.hpp"
#include "trivar/core/memory_budget.hpp"
#include "trivar/core/parallel.hpp"

namespace trivar {

TSplineTriangulation tessellate(const TSplineSurface& surface, double tolerance, int max_per_element, int threads) {
  require(tolerance > 0 && std::isfinite(tolerance), "tessellate: the chordal tolerance must be positive");
  require(max_per_element >= 1, "tessellate: at least one subdivision per element");
  // The grid lines, from the elements (they are its cells).
  std::array<std::vector<double>, 2> lines;
  for (const Box<2>& e : surface.elements())
    for (int k = 0; k < 2; ++k) {
      lines[k].push_back(e.lo[k]);
      lines[k].push_back(e.hi[k]);
    }
  for (auto& l : lines) {
    std::sort(l.begin(), l.end());
    l.erase(std::unique(l.begin(), l.end()), l.end());
  }
  const auto cell = [&](int k, double x) {
    return static_cast<std::size_t>(std::lower_bound(lines[k].begin(), lines[k].end(), x) - lines[k].begin());
  };
  std::array<std::vector<int>, 2> count{std::vector<int>(lines[0].size() - 1, 1), std::vector<int>(lines[1].size() - 1, 1)};
  const int p = surface.degrees()[0], q = surface.degrees()[1];
  const auto& nets = surface.bezier_elements();
  const auto& elements = surface.elements();
  for (std::size_t e = 0; e < elements.size(); ++e) {
    const BezierElement<2>& z = nets[e];
    const auto at = [&](int i, int j, int d) {
      const double* c = z.coefs.data() + 4 * static_cast<std::size_t>(i + (p + 1) * j);
      return c[d] / c[3];
    };
    double duu = 0, dvv = 0, duv = 0;
    for (int j = 0; j <= q; ++j)
      for (int i = 0; i <= p; ++i) {
        double a = 0, b = 0, c = 0;
        for (int d = 0; d < 3; ++d) {
          if (i + 2 <= p) a += std::pow(at(i + 2, j, d) - 2 * at(i + 1, j, d) + at(i, j, d), 2);
          if (j + 2 <= q) b += std::pow(at(i, j + 2, d) - 2 * at(i, j + 1, d) + at(i, j, d), 2);
          if (i + 1 <= p && j + 1 <= q) c += std::pow(at(i + 1, j + 1, d) - at(i + 1, j, d) - at(i, j + 1, d) + at(i, j, d), 2);
        }
        duu = std::max(duu, std::sqrt(a) * p * (p - 1));
        dvv = std::max(dvv, std::sqrt(b) * q * (q - 1));
        duv = std::max(duv, std::sqrt(c) * p * q);
      }
    // A third of the budget per term: D / (8 n^2) <= tol / 3, and the mixed term with n_u = n_v = max.
    const auto need = [&](double D) {
      return clamped_count(std::sqrt(3.0 * D / (8.0 * tolerance)), 1, max_per_element);
    };
    int nu = need(duu), nv = need(dvv);
    const int nm = need(2.0 * duv);
    nu = std::max(nu, nm);
    nv = std::max(nv, nm);
    auto& cu = count[0][cell(0, elements[e].lo[0])];
    auto& cv = count[1][cell(1, elements[e].lo[1])];
    cu = std::max(cu, nu);
    cv = std::max(cv, nv);
  }
  // The lattice of sample parameters per direction.
  std::array<std::vector<double>, 2> samples;
  std::array<std::vector<int>, 2> first;  // lattice index of each grid line
  for (int k = 0; k < 2; ++k) {
    for (std::size_t c = 0; c + 1 < lines[k].size(); ++c) {
      first[k].push_back(static_cast<int>(samples[k].size()));
      const int n = count[k][c];
      for (int i = 0; i < n; ++i) samples[k].push_back(lines[k][c] + (lines[k][c + 1] - lines[k][c]) * i / n);
    }
    first[k].push_back(static_cast<int>(samples[k].size()));
    samples[k].push_back(lines[k].back());
  }
  const std::size_t ns = samples[0].size(), nt = samples[1].size();
  require_memory(static_cast<double>(ns) * static_cast<double>(nt) * (4.0 + 2 * 24.0 + 2 * 12.0),
                 "a T-spline tessellation on a " + std::to_string(ns) + " x " + std::to_string(nt) + " sample lattice");
  // Lattice points used by an element get an id.
  std::vector<int> id(ns * nt, -1);
  TSplineTriangulation out;
  std::vector<int> owner;
  for (std::size_t en = 0; en < elements.size(); ++en) {
    const Box<2>& e = elements[en];
    const std::size_t i0 = static_cast<std::size_t>(first[0][cell(0, e.lo[0])]), i1 = static_cast<std::size_t>(first[0][cell(0, e.hi[0])]);
    const std::size_t j0 = static_cast<std::size_t>(first[1][cell(1, e.lo[1])]), j1 = static_cast<std::size_t>(first[1][cell(1, e.hi[1])]);
    for (std::size_t j = j0; j <= j1; ++j)
      for (std::size_t i = i0; i <= i1; ++i) {
        int& v = id[i + ns * j];
        if (v < 0) {
          v = static_cast<int>(out.params.size());
          out.params.push_back({samples[0][i], samples[1][j]});
          owner.push_back(static_cast<int>(en));
        }
      }
    for (std::size_t j = j0; j < j1; ++j)
      for (std::size_t i = i0; i < i1; ++i) {
        const int a = id[i + ns * j], b = id[i + 1 + ns * j], c = id[i + 1 + ns * (j + 1)], d = id[i + ns * (j + 1)];
        out.triangles.push_back({a, b, c});
        out.triangles.push_back({a, c, d});
      }
  }
  out.points.resize(out.params.size());
  parallel_for(static_cast<std::ptrdiff_t>(out.params.size()), threads, [&](std::ptrdiff_t i) {
    const auto& u = out.params[static_cast<std::size_t>(i)];
    surface.eval_on_element(owner[static_cast<std::size_t>(i)], {u[0], u[1]}, out.points[static_cast<std::size_t>(i)].data());
  });
  return out;
}

}  // namespace trivar
