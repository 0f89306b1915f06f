#include "trivar/lr/dimension_formula.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include "trivar/core/error.hpp"

namespace trivar {

namespace {

// The mesh on the grid of all distinct line values: multiplicity of every grid segment (0 when not in the mesh)
// and, per interior edge / vertex, the weights' multiplicities.
struct GridMesh {
  std::vector<double> x, y;
  std::vector<int> mu_u;  // segment on u = x[i] between y[j], y[j+1]: index i * (ny - 1) + j
  std::vector<int> mu_v;  // segment on v = y[j] between x[i], x[i+1]: index j * (nx - 1) + i
  int nx() const { return static_cast<int>(x.size()); }
  int ny() const { return static_cast<int>(y.size()); }
  int u(int i, int j) const { return (j < 0 || j >= ny() - 1) ? 0 : mu_u[static_cast<std::size_t>(i * (ny() - 1) + j)]; }
  int v(int i, int j) const { return (i < 0 || i >= nx() - 1) ? 0 : mu_v[static_cast<std::size_t>(j * (nx() - 1) + i)]; }
  bool vertex(int i, int j) const { return (u(i, j - 1) || u(i, j)) && (v(i - 1, j) || v(i, j)); }
};

int index_of(const std::vector<double>& vals, double t) {
  return static_cast<int>(std::lower_bound(vals.begin(), vals.end(), t) - vals.begin());
}

GridMesh grid_mesh(std::span<const MeshRectangle<2>> mesh) {
  require(!mesh.empty(), "dimension formula: empty mesh");
  GridMesh g;
  for (const auto& r : mesh) {
    require(r.dir == 0 || r.dir == 1, "dimension formula: mesh rectangle direction outside 0..1");
    require(r.multiplicity >= 1, "dimension formula: mesh rectangle multiplicity below 1");
    const int o = 1 - r.dir;
    auto& along = r.dir == 0 ? g.x : g.y;
    auto& across = r.dir == 0 ? g.y : g.x;
    along.push_back(r.value);
    across.push_back(r.extent.lo[o]);
    across.push_back(r.extent.hi[o]);
  }
  for (auto* v : {&g.x, &g.y}) {
    std::sort(v->begin(), v->end());
    v->erase(std::unique(v->begin(), v->end()), v->end());
  }
  const int nx = g.nx(), ny = g.ny();
  require(nx >= 2 && ny >= 2, "dimension formula: the mesh does not bound a two-dimensional domain");
  g.mu_u.assign(static_cast<std::size_t>(nx * (ny - 1)), 0);
  g.mu_v.assign(static_cast<std::size_t>(ny * (nx - 1)), 0);
  for (const auto& r : mesh) {
    const int o = 1 - r.dir;
    const auto& along = r.dir == 0 ? g.x : g.y;
    const auto& across = r.dir == 0 ? g.y : g.x;
    const int i = index_of(along, r.value), j0 = index_of(across, r.extent.lo[o]), j1 = index_of(across, r.extent.hi[o]);
    for (int j = j0; j < j1; ++j) {
      int& m = r.dir == 0 ? g.mu_u[static_cast<std::size_t>(i * (ny - 1) + j)]
                          : g.mu_v[static_cast<std::size_t>(i * (nx - 1) + j)];
      m = std::max(m, r.multiplicity);
    }
  }
  return g;
}

// One multiplicity through a vertex: the non-zero ones of the two sides must agree.
int through(int a, int b, double x, double y) {
  require(!(a && b && a != b), [&] {
    return "dimension formula: mesh line multiplicity changes from " + std::to_string(a) + " to " + std::to_string(b) +
           " at the vertex (" + std::to_string(x) + ", " + std::to_string(y) + ")";
  });
  return std::max(a, b);
}

// Visits every interior edge (dir, multiplicity) and interior vertex (mu_u, mu_v), and counts elements.
template <class Edge, class Vertex>
int walk(const GridMesh& g, Edge&& edge, Vertex&& vertex) {
  const int nx = g.nx(), ny = g.ny();
  int elements = 0;
  for (int i = 0; i + 1 < nx; ++i)
    for (int j = 0; j + 1 < ny; ++j)
      if ((i == 0 || g.u(i, j)) && (j == 0 || g.v(i, j))) ++elements;
  for (int i = 1; i + 1 < nx; ++i)
    for (int j = 0; j + 1 < ny; ++j) {
      const int m = g.u(i, j);
      if (!m) continue;
      if (j == 0 || g.vertex(i, j) || !g.u(i, j - 1))
        edge(0, m);
      else
        through(g.u(i, j - 1), m, g.x[static_cast<std::size_t>(i)], g.y[static_cast<std::size_t>(j)]);
    }
  for (int j = 1; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i) {
      const int m = g.v(i, j);
      if (!m) continue;
      if (i == 0 || g.vertex(i, j) || !g.v(i - 1, j))
        edge(1, m);
      else
        through(g.v(i - 1, j), m, g.x[static_cast<std::size_t>(i)], g.y[static_cast<std::size_t>(j)]);
    }
  for (int i = 1; i + 1 < nx; ++i)
    for (int j = 1; j + 1 < ny; ++j)
      if (g.vertex(i, j)) {
        const double x = g.x[static_cast<std::size_t>(i)], y = g.y[static_cast<std::size_t>(j)];
        vertex(through(g.u(i, j - 1), g.u(i, j), x, y), through(g.v(i - 1, j), g.v(i, j), x, y));
      }
  return elements;
}

// r + 1 for multiplicity mu, at least 0 (mu = p + 1 is a C^-1 line).
long long smooth1(int p, int mu) { return std::max(0, p - mu + 1); }

}  // namespace

TMeshCounts tmesh_counts(std::span<const MeshRectangle<2>> mesh) {
  const GridMesh g = grid_mesh(mesh);
  TMeshCounts c;
  c.elements = walk(
      g, [&](int dir, int) { ++(dir == 0 ? c.edges_const_u : c.edges_const_v); },
      [&](int, int) { ++c.interior_vertices; });
  return c;
}

long long dimension_from_counts(const Ints<2>& degrees, const Ints<2>& smoothness, const TMeshCounts& c) {
  const long long p0 = degrees[0], p1 = degrees[1], r0 = smoothness[0], r1 = smoothness[1];
  require(p0 >= 0 && p1 >= 0 && r0 >= -1 && r0 <= p0 && r1 >= -1 && r1 <= p1,
          "dimension_from_counts: degrees must be >= 0 and smoothness in -1..p");
  return (p0 + 1) * (p1 + 1) * c.elements - (p1 + 1) * (r0 + 1) * c.edges_const_u -
         (p0 + 1) * (r1 + 1) * c.edges_const_v + (r0 + 1) * (r1 + 1) * c.interior_vertices;
}

long long dimension(std::span<const MeshRectangle<2>> mesh, const Ints<2>& degrees) {
  require(degrees[0] >= 0 && degrees[1] >= 0, "dimension formula: negative degree");
  const GridMesh g = grid_mesh(mesh);
  const long long p0 = degrees[0], p1 = degrees[1];
  long long dim = 0;
  const int elements = walk(
      g,
      [&](int dir, int mu) {
        dim -= dir == 0 ? (p1 + 1) * smooth1(degrees[0], mu) : (p0 + 1) * smooth1(degrees[1], mu);
      },
      [&](int mu_u, int mu_v) { dim += smooth1(degrees[0], mu_u) * smooth1(degrees[1], mu_v); });
  return dim + (p0 + 1) * (p1 + 1) * elements;
}

HandInHand hand_in_hand(int basis_count, std::span<const MeshRectangle<2>> mesh, const Ints<2>& degrees) {
  HandInHand h;
  h.basis_count = basis_count;
  h.dimension = dimension(mesh, degrees);
  h.status = basis_count > h.dimension    ? Independence::not_independent
             : basis_count == h.dimension ? Independence::independent
                                          : Independence::not_tested;
  return h;
}

}  // namespace trivar
