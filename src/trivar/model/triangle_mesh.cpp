#include "trivar/model/triangle_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <unordered_set>

namespace trivar {

namespace {

using Vec = std::array<double, 3>;

Vec sub(const Vec& a, const Vec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

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

}  // namespace trivar
