#include "trivar/iga/tensor_space.hpp"

#include <string>

#include "trivar/core/error.hpp"
#include "trivar/spline/degree_elevation.hpp"
#include "trivar/spline/knot_insertion.hpp"

namespace trivar {

template <int D>
TensorSpace<D> make_tensor_space(const TensorSpline<D>& geometry, int degree, int subdivisions) {
  require(geometry.dim() == D, "iga: a " + std::to_string(D) + "-D analysis needs a geometry with " +
                                   std::to_string(D) + " coordinates, got " + std::to_string(geometry.dim()));
  require(degree >= 1, "iga: degree must be at least 1, got " + std::to_string(degree));
  require(subdivisions >= 1, "iga: refinement must be at least 1, got " + std::to_string(subdivisions));
  for (int k = 0; k < D; ++k)
    require(geometry.knots(k).is_clamped(),
            "iga: knot vector " + std::to_string(k) + " is not clamped (boundary conditions need open knots)");
  Ints<D> by{}, n{};
  for (int k = 0; k < D; ++k) {
    by[k] = std::max(0, degree - geometry.degree(k));
    n[k] = subdivisions;
  }
  return {refine_uniform(elevate_degree(geometry, by), n)};
}

template <int D>
TensorSpline<D> box_geometry(const Param<D>& lo, const Param<D>& hi, int degree,
                             int elements) {
  require(degree >= 1, "iga: degree must be at least 1, got " + std::to_string(degree));
  require(elements >= 1, "iga: refinement must be at least 1, got " + std::to_string(elements));
  std::array<KnotVector, D> knots;
  std::array<std::vector<double>, D> g;
  for (int k = 0; k < D; ++k) {
    knots[k] = KnotVector::open_uniform(degree, elements);
    g[k] = knots[k].greville();
  }
  int total = 1;
  for (int k = 0; k < D; ++k) total *= knots[k].size();
  std::vector<double> coefs;
  coefs.reserve(static_cast<std::size_t>(total) * D);
  for (int i = 0; i < total; ++i)
    for (int k = 0, rest = i; k < D; rest /= knots[k].size(), ++k)
      coefs.push_back(lo[k] + (hi[k] - lo[k]) * g[k][static_cast<std::size_t>(rest % knots[k].size())]);
  return TensorSpline<D>(knots, D, false, std::move(coefs));
}

template <int D>
std::vector<int> face_basis(const TensorSpace<D>& space, const Face& face) {
  const auto& g = space.geometry;
  const int fixed = face.side == 0 ? 0 : g.count(face.dir) - 1;
  std::vector<int> ids;
  for (int i = 0; i < g.num_coefs(); ++i)
    if (g.multi_index(i)[face.dir] == fixed) ids.push_back(i);
  return ids;
}

template <int D>
std::vector<Face> all_faces() {
  std::vector<Face> f;
  for (int k = 0; k < D; ++k)
    for (int s = 0; s < 2; ++s) f.push_back({k, s});
  return f;
}

#define TRIVAR_INSTANTIATE(D)                                                                                  \
  template TensorSpace<D> make_tensor_space(const TensorSpline<D>&, int, int);                                 \
  template TensorSpline<D> box_geometry<D>(const Param<D>&, const Param<D>&, int, int);                     \
  template std::vector<int> face_basis(const TensorSpace<D>&, const Face&);                                    \
  template std::vector<Face> all_faces<D>();
TRIVAR_INSTANTIATE(2)
TRIVAR_INSTANTIATE(3)
#undef TRIVAR_INSTANTIATE

}  // namespace trivar
