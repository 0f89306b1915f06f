#include "trivar/model/coons.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "trivar/core/error.hpp"
#include "trivar/core/number_format.hpp"
#include "trivar/spline/compatibility.hpp"
#include "trivar/spline/iso_extraction.hpp"
#include "trivar/spline/reparametrization.hpp"
#include "trivar/spline/split.hpp"

namespace trivar {

namespace {

constexpr std::array<std::array<int, 2>, 3> kOther{{{1, 2}, {0, 2}, {0, 1}}};
constexpr std::array<const char*, 6> kFaceName{"u=0", "u=1", "v=0", "v=1", "w=0", "w=1"};
constexpr std::array<char, 3> kDirName{'u', 'v', 'w'};

int face_index(int normal, int side) { return 2 * normal + side; }

// The volume that is parts[bits] in the directions `spline_dirs` (increasing) and linear in the others, with
// bit j of the part index giving the side of the j-th linear direction. parts share one spline space.
template <int E>
SplineVolume linear_blend(const std::vector<TensorSpline<E>>& parts, const std::array<int, E>& spline_dirs,
                          const Box<3>& domain) {
  std::array<KnotVector, 3> kv;
  std::array<int, 3> local{-1, -1, -1};
  for (int e = 0; e < E; ++e) local[spline_dirs[e]] = e;
  for (int d = 0; d < 3; ++d)
    kv[d] = local[d] >= 0 ? parts[0].knots(local[d])
                          : KnotVector(1, {domain.lo[d], domain.lo[d], domain.hi[d], domain.hi[d]});
  const int stride = parts[0].stride();
  const std::array<int, 3> n{kv[0].size(), kv[1].size(), kv[2].size()};
  std::vector<double> h(static_cast<std::size_t>(n[0]) * n[1] * n[2] * stride);
  std::size_t out = 0;
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        const std::array<int, 3> idx{i, j, k};
        int part = 0, bit = 0;
        typename TensorSpline<E>::Index li{};
        for (int d = 0; d < 3; ++d) {
          if (local[d] >= 0)
            li[local[d]] = idx[d];
          else
            part |= idx[d] << bit++;
        }
        const double* c = parts[part].coef(parts[part].linear_index(li));
        std::copy_n(c, stride, h.data() + out);
        out += static_cast<std::size_t>(stride);
      }
  return SplineVolume(std::move(kv), parts[0].dim(), parts[0].is_rational(), std::move(h));
}

// The curve of degree 1 through the end coefficients of a clamped curve: its linear interpolant.
SplineCurve chord(const SplineCurve& c) {
  const KnotVector& kv = c.knots(0);
  const auto st = static_cast<std::size_t>(c.stride());
  std::vector<double> h(c.coef(0), c.coef(0) + st);
  h.insert(h.end(), c.coef(c.num_coefs() - 1), c.coef(c.num_coefs() - 1) + st);
  return SplineCurve({KnotVector(1, {kv.start(), kv.start(), kv.end(), kv.end()})}, c.dim(), c.is_rational(),
                     std::move(h));
}

}  // namespace

SplineVolume coons_volume(const std::array<SplineSurface, 6>& faces, double tolerance) {
  for (int f = 1; f < 6; ++f)
    require(faces[f].dim() == faces[0].dim(), [&] {
      return std::string("coons_volume: face ") + kFaceName[f] + " has control dimension " +
             std::to_string(faces[f].dim()) + ", face u=0 has " + std::to_string(faces[0].dim());
    });

  Box<3> domain;
  const std::array<const KnotVector*, 3> reference{&faces[2].knots(0), &faces[0].knots(0), &faces[0].knots(1)};
  for (int d = 0; d < 3; ++d) {
    domain.lo[d] = reference[d]->start();
    domain.hi[d] = reference[d]->end();
  }
  std::array<SplineSurface, 6> face;
  for (int f = 0; f < 6; ++f) {
    face[f] = faces[f];
    bool clamped = true;
    for (int e = 0; e < 2; ++e) {
      const int d = kOther[f / 2][e];
      clamped = clamped && face[f].knots(e).is_clamped();
      if (face[f].knots(e).start() != domain.lo[d] || face[f].knots(e).end() != domain.hi[d])
        face[f] = reparametrize(face[f], e, domain.lo[d], domain.hi[d]);
    }
    // Corner values are read off end coefficients below.
    if (!clamped) face[f] = sub_patch(face[f], face[f].domain());
  }

  // edges[d][s1 + 2 s2]: the edge along d where the other directions (n1 < n2) are at sides s1, s2.
  std::array<std::vector<SplineCurve>, 3> edges;
  for (int d = 0; d < 3; ++d) {
    const int n1 = kOther[d][0], n2 = kOther[d][1];
    for (int s2 = 0; s2 < 2; ++s2)
      for (int s1 = 0; s1 < 2; ++s1) {
        const int fa = face_index(n1, s1), fb = face_index(n2, s2);
        // Position of the fixed direction among each face's two parameters.
        const int ea = kOther[n1][0] == n2 ? 0 : 1, eb = kOther[n2][0] == n1 ? 0 : 1;
        const SplineCurve a = iso_extract(face[fa], ea, s2 ? domain.hi[n2] : domain.lo[n2]);
        const SplineCurve b = iso_extract(face[fb], eb, s1 ? domain.hi[n1] : domain.lo[n1]);
        const auto c = make_compatible<1>({a, b});
        double gap = 0;
        for (std::size_t i = 0; i < c[0].coefs().size(); ++i)
          gap = std::max(gap, std::abs(c[0].coefs()[i] - c[1].coefs()[i]));
        require(gap <= tolerance, [&] {
          return std::string("coons_volume: faces ") + kFaceName[fa] + " and " + kFaceName[fb] +
                 " disagree on their shared edge along " + kDirName[d] + " (" + kDirName[n1] + "=" +
                 std::to_string(s1) + ", " + kDirName[n2] + "=" + std::to_string(s2) + ") by " + format_number(gap) +
                 " > tolerance " + format_number(tolerance);
        });
        edges[d].push_back(a);
      }
  }

  std::vector<SplineVolume> terms;
  for (int n = 0; n < 3; ++n)
    terms.push_back(linear_blend<2>(make_compatible<2>({face[face_index(n, 0)], face[face_index(n, 1)]}),
                                    kOther[n], domain));
  for (int d = 0; d < 3; ++d) terms.push_back(linear_blend<1>(make_compatible(edges[d]), {d}, domain));
  std::vector<SplineCurve> chords;
  for (const auto& e : edges[2]) chords.push_back(chord(e));
  terms.push_back(linear_blend<1>(make_compatible(chords), {2}, domain));

  const auto c = make_compatible(terms);
  constexpr std::array<double, 7> sign{1, 1, 1, -1, -1, -1, 1};
  std::vector<double> h(c[0].coefs().size(), 0.0);
  for (std::size_t t = 0; t < c.size(); ++t)
    for (std::size_t i = 0; i < h.size(); ++i) h[i] += sign[t] * c[t].coefs()[i];
  return SplineVolume(c[0].knot_vectors(), c[0].dim(), c[0].is_rational(), std::move(h));
}

}  // namespace trivar
