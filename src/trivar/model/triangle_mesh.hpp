#pragma once
// TriangleMesh: an indexed triangle mesh (shared vertices), the form in which trivar hands model boundaries to
// STL, 3MF and AMF writers; with the checks and integrals those outputs are validated by.
#include <array>
#include <vector>

namespace trivar {

struct TriangleMesh {
  std::vector<std::array<double, 3>> vertices;
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise seen from outside
};

// True when every undirected edge is used by exactly two triangles, once in each direction (a closed,
// consistently oriented 2-manifold).
bool is_watertight(const TriangleMesh& m);

double surface_area(const TriangleMesh& m);

// V - E + F of the mesh (vertices used by some triangle, distinct undirected edges, triangles): 2 - 2g for a
// closed orientable surface of genus g, summed over its components.
int euler_characteristic(const TriangleMesh& m);

// Barycentric coordinates of the point of triangle abc closest to p (Ericson, Real-Time Collision Detection,
// 5.1.5).
std::array<double, 3> closest_on_triangle(const std::array<double, 3>& p, const std::array<double, 3>& a,
                                          const std::array<double, 3>& b, const std::array<double, 3>& c);

// Signed enclosed volume by the divergence theorem (positive for outward-oriented closed meshes).
double enclosed_volume(const TriangleMesh& m);

}  // namespace trivar
