#include "trivar/iga/multipatch_space.hpp"

#include <cmath>
#include <numeric>
#include <string>

#include "trivar/core/error.hpp"
#include "trivar/model/vmodel.hpp"

namespace trivar {

namespace {

// Union-find over (patch, local basis function) pairs flattened to one index.
class Identification {
public:
  explicit Identification(int n) : parent_(static_cast<std::size_t>(n)) {
    std::iota(parent_.begin(), parent_.end(), 0);
  }
  int find(int a) {
    while (parent_[static_cast<std::size_t>(a)] != a) {
      parent_[static_cast<std::size_t>(a)] = parent_[static_cast<std::size_t>(parent_[static_cast<std::size_t>(a)])];
      a = parent_[static_cast<std::size_t>(a)];
    }
    return a;
  }
  void join(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) parent_[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
  }

private:
  std::vector<int> parent_;
};

// The local basis function at face grid position (s, t) of a cell face (face_param_dirs order).
int face_function(const TensorSpline<3>& g, int face, int s, int t) {
  const auto [a, b] = face_param_dirs(face);
  Ints<3> i{};
  i[face_direction(face)] = face_side(face) == 0 ? 0 : g.count(face_direction(face)) - 1;
  i[a] = s;
  i[b] = t;
  return g.linear_index(i);
}

double distance(const TensorSpline<3>& ga, int ia, const TensorSpline<3>& gb, int ib) {
  double xa[3], xb[3];
  ga.control_point(ia, xa);
  gb.control_point(ib, xb);
  return std::hypot(xa[0] - xb[0], xa[1] - xb[1], xa[2] - xb[2]);
}

std::string where(int cell, int face) {
  static const char* names[] = {"u0", "u1", "v0", "v1", "w0", "w1"};
  return "cell " + std::to_string(cell) + " face " + names[face];
}

}  // namespace

template <int D>
MultipatchSpace<D> single_patch_space(TensorSpace<D> space) {
  MultipatchSpace<D> m;
  m.num_basis = space.num_basis();
  m.global.emplace_back(static_cast<std::size_t>(m.num_basis));
  std::iota(m.global[0].begin(), m.global[0].end(), 0);
  m.boundary = all_faces<D>();
  m.patches.push_back(std::move(space));
  return m;
}

MultipatchSpace<3> multipatch_space(const VModel& model, int degree, int subdivisions) {
  const VTopology& topo = model.topology();
  if (!topo.non_conforming.empty())
    throw Error("iga: " + topo.non_conforming.front().describe() +
                "; analysis needs conforming faces (identical knots, degrees and control points)");
  MultipatchSpace<3> m;
  std::vector<int> offset{0};
  for (int c = 0; c < model.num_cells(); ++c) {
    m.patches.push_back(make_tensor_space(model.cell(c).geometry(), degree, subdivisions));
    offset.push_back(offset.back() + m.patches.back().num_basis());
  }
  Identification same(offset.back());
  // Coincident control points of shared faces are equal up to the gluing tolerance; refinement is exact, so a
  // larger gap means the faces were not refined alike.
  const double tol = 10 * topo.tolerance;
  for (std::size_t h = 0; h < topo.halves.size(); ++h) {
    const HalfVSurface& half = topo.halves[h];
    const TensorSpline<3>& ga = m.patches[static_cast<std::size_t>(half.cell)].geometry;
    const auto [a, b] = face_param_dirs(half.face);
    const int ns = ga.count(a), nt = ga.count(b);
    if (half.degenerate) {
      // A face collapsed to a curve or a point: functions at the same point are one.
      for (int s = 0; s < ns; ++s)
        for (int t = 0; t < nt; ++t)
          for (int s2 = 0; s2 < ns; ++s2)
            for (int t2 = 0; t2 < nt; ++t2) {
              const int i = face_function(ga, half.face, s, t), j = face_function(ga, half.face, s2, t2);
              if (i < j && distance(ga, i, ga, j) <= tol) same.join(offset[half.cell] + i, offset[half.cell] + j);
            }
      continue;
    }
    if (half.twin < 0) {
      m.boundary.push_back({face_direction(half.face), face_side(half.face), half.cell});
      continue;
    }
    if (half.twin < static_cast<int>(h)) continue;
    const HalfVSurface& twin = topo.halves[static_cast<std::size_t>(half.twin)];
    const TensorSpline<3>& gb = m.patches[static_cast<std::size_t>(twin.cell)].geometry;
    const auto [a2, b2] = face_param_dirs(twin.face);
    const FaceOrientation& o = half.to_twin;
    const int ms = o.swap ? nt : ns, mt = o.swap ? ns : nt;
    require(gb.count(a2) == ms && gb.count(b2) == mt,
            "iga: " + where(half.cell, half.face) + " and " + where(twin.cell, twin.face) +
                " have different numbers of basis functions after refinement");
    for (int s = 0; s < ns; ++s)
      for (int t = 0; t < nt; ++t) {
        const int x = o.swap ? t : s, y = o.swap ? s : t;
        const int s2 = o.flip_s ? ms - 1 - x : x, t2 = o.flip_t ? mt - 1 - y : y;
        const int i = face_function(ga, half.face, s, t), j = face_function(gb, twin.face, s2, t2);
        require(distance(ga, i, gb, j) <= tol, "iga: the refined control nets of " + where(half.cell, half.face) +
                                                   " and " + where(twin.cell, twin.face) + " do not coincide");
        same.join(offset[half.cell] + i, offset[twin.cell] + j);
      }
  }
  std::vector<int> number(static_cast<std::size_t>(offset.back()), -1);
  for (int c = 0; c < model.num_cells(); ++c) {
    std::vector<int>& g =
        m.global.emplace_back(static_cast<std::size_t>(m.patches[static_cast<std::size_t>(c)].num_basis()));
    for (std::size_t i = 0; i < g.size(); ++i) {
      int& n = number[static_cast<std::size_t>(same.find(offset[c] + static_cast<int>(i)))];
      if (n < 0) n = m.num_basis++;
      g[i] = n;
    }
  }
  return m;
}

template <int D>
Eigen::VectorXd patch_coefs(const MultipatchSpace<D>& space, int patch, const Eigen::VectorXd& coefs,
                            int components) {
  const std::vector<int>& g = space.global[static_cast<std::size_t>(patch)];
  const int n = static_cast<int>(g.size());
  Eigen::VectorXd out(static_cast<Eigen::Index>(n) * components);
  for (int c = 0; c < components; ++c)
    for (int i = 0; i < n; ++i)
      out[static_cast<Eigen::Index>(c) * n + i] =
          coefs[static_cast<Eigen::Index>(c) * space.num_basis + g[static_cast<std::size_t>(i)]];
  return out;
}

#define TRIVAR_INSTANTIATE(D)                                                  \
  template MultipatchSpace<D> single_patch_space(TensorSpace<D>);              \
  template Eigen::VectorXd patch_coefs(const MultipatchSpace<D>&, int, const Eigen::VectorXd&, int);
TRIVAR_INSTANTIATE(2)
TRIVAR_INSTANTIATE(3)
#undef TRIVAR_INSTANTIATE

}  // namespace trivar
