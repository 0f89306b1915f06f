#include "trivar/model/triangle_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <unordered_set>

#include "trivar/core/vec3.hpp"

namespace trivar {

namespace {

using Vec = Vec3;

}  // namespace

bool is_watertight(const TriangleMesh& m) {
  // Directed edge (a, b) counts +1 at key(min, max) when a < b and +2^32 when a > b: a closed oriented
  // manifold has exactly one of each for every edge.
  if (m.triangles.empty()) return false;  // nothing encloses a volume
  std::unordered_map<std::uint64_t, std::uint64_t> uses;
  uses.reserve(m.triangles.size() * 3);
  const auto n = static_cast<std::uint64_t>(m.vertices.size());
  for (const auto& t : m.triangles)
    for (int e = 0; e < 3; ++e) {
      const auto a = static_cast<std::uint64_t>(t[e]), b = static_cast<std::uint64_t>(t[(e + 1) % 3]);
      if (a == b || a >= n || b >= n) return false;
      uses[std::min(a, b) * n + std::max(a, b)] += a < b ? 1 : (std::uint64_t{1} << 32);
    }
  return std::all_of(uses.begin(), uses.end(), [](const auto& kv) { return kv.second == 1 + (std::uint64_t{1} << 32); });
}

int euler_characteristic(const TriangleMesh& m) {
  std::unordered_set<std::uint64_t> edges;
  std::unordered_set<int> vertices;
  const auto n = static_cast<std::uint64_t>(m.vertices.size());
  for (const auto& t : m.triangles)
    for (int e = 0; e < 3; ++e) {
      vertices.insert(t[e]);
      const auto a = static_cast<std::uint64_t>(t[e]), b = static_cast<std::uint64_t>(t[(e + 1) % 3]);
      edges.insert(std::min(a, b) * n + std::max(a, b));
    }
  return static_cast<int>(vertices.size()) - static_cast<int>(edges.size()) + static_cast<int>(m.triangles.size());
}

double surface_area(const TriangleMesh& m) {
  double a = 0;
  for (const auto& t : m.triangles) {
    const Vec c = cross(sub(m.vertices[t[1]], m.vertices[t[0]]), sub(m.vertices[t[2]], m.vertices[t[0]]));
    a += 0.5 * std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
  }
  return a;
}

double enclosed_volume(const TriangleMesh& m) {
  double v = 0;
  for (const auto& t : m.triangles) {
    const Vec& a = m.vertices[t[0]];
    const Vec c = cross(m.vertices[t[1]], m.vertices[t[2]]);
    v += a[0] * c[0] + a[1] * c[1] + a[2] * c[2];
  }
  return v / 6.0;
}

std::array<double, 3> closest_on_triangle(const std::array<double, 3>& p, const std::array<double, 3>& a,
                                          const std::array<double, 3>& b, const std::array<double, 3>& c) {
  const Vec ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
  const Vec bp = sub(p, b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return {1 - v, v, 0};
  }
  const Vec cp = sub(p, c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return {1 - w, 0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - w, w};
  }
  const double denom = 1 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return {1 - v - w, v, w};
}

}  // namespace trivar
