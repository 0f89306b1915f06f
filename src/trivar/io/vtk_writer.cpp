#include "trivar/io/vtk_writer.hpp"

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <limits>
#include <cstdint>
#include <type_traits>

#include "trivar/core/error.hpp"
#include "trivar/core/memory_budget.hpp"
#include "trivar/io/vtk_cell_order.hpp"
#include "trivar/io/vtu_fields.hpp"
#include "trivar/io/vtu_file.hpp"
#include "trivar/spline/bernstein_interpolation.hpp"
#include "trivar/spline/bezier_extraction.hpp"

namespace trivar::io {

namespace {

constexpr std::array<const char*, 5> kReservedNames = {"param", "RationalWeights", "higher_components", "element",
                                                       "direction"};

// One <Piece>: everything per point and per cell, already in VTK layout.
struct SplinePiece {
  std::vector<double> points;   // 3 per point
  std::vector<double> params;   // 3 per point
  std::vector<double> weights;  // 1 per point, Bezier mode only
  std::vector<double> higher;   // `extra` per point
  std::vector<std::vector<double>> fields;
  std::vector<std::int64_t> connectivity, offsets;
  std::vector<std::uint8_t> types;
  std::vector<std::int32_t> element, degrees;  // element: or direction (control net); degrees: Bezier mode only
  bool rational = false;                       // Bezier mode: some element has weights other than 1
  // Bezier mode: the points of every element in its own node order (first direction fastest), for turning
  // field values at the nodes into Bezier coefficients.
  std::vector<std::int64_t> element_nodes;
  std::vector<int> element_degrees;  // Bezier mode: the same for every element of a tensor spline

  void add_point(const double* x, int dim, int extra, const double* u, int D) {
    for (int d = 0; d < 3; ++d) points.push_back(d < dim ? x[d] : 0.0);
    for (int d = 0; d < extra; ++d) higher.push_back(3 + d < dim ? x[3 + d] : 0.0);
    for (int k = 0; k < 3; ++k) params.push_back(k < D ? u[k] : 0.0);
  }
  // Called after the cell's points were appended to `connectivity` (VTK offsets mark cell ends).
  void end_cell(int type, int elem) {
    types.push_back(static_cast<std::uint8_t>(type));
    element.push_back(elem);
    offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
  }
  std::int64_t num_points() const { return static_cast<std::int64_t>(points.size() / 3); }
};

// Discontinuous across an interior breakpoint: knot multiplicity p + 1 (C^-1).
bool discontinuous_at(const KnotVector& kv, double b) { return kv.multiplicity(b) > kv.degree(); }

template <int D>
long long product(const std::array<int, D>& n) {
  long long r = 1;
  for (int k = 0; k < D; ++k) r *= n[k];
  return r;
}

// Calls f(i) for every multi-index 0 <= i < n, first index fastest.
template <int D, class F>
void for_each_index(const std::array<int, D>& n, F&& f) {
  if (product<D>(n) == 0) return;
  std::array<int, D> i{};
  while (true) {
    f(i);
    int k = 0;
    while (k < D && ++i[k] == n[k]) i[k++] = 0;
    if (k == D) return;
  }
}

template <int D>
int linear(const std::array<int, D>& i, const std::array<int, D>& n) {
  int l = 0;
  for (int k = D - 1; k >= 0; --k) l = l * n[k] + i[k];
  return l;
}

// Refuses a piece of more points than VTK's 32-bit point ids of a piece allow, or than memory holds: per point
// coordinates, parameters, weight, higher components and the caller's fields, per cell its connectivity.
template <int D>
void check_size(const std::array<int, D>& n, const std::string& path, int per_point, double cells, int per_cell) {
  long long total = 1;
  for (int k = 0; k < D; ++k) {
    total *= n[k];
    require(total <= INT_MAX, path + ": too many points for one VTU piece");
  }
  require_memory(8.0 * (static_cast<double>(total) * per_point + cells * (per_cell + 3)),
                 path + ": VTU output of " + std::to_string(total) + " points");
}

template <int D>
void add_sampled(SplinePiece& piece, const TensorSpline<D>& s, int n, int extra, int field_values, const std::string& path) {
  // Per direction: sample parameters and, per element, the index of its first sample.
  std::array<std::vector<double>, D> u;
  std::array<std::vector<int>, D> first;
  std::array<int, D> ne, nu;
  for (int k = 0; k < D; ++k) {
    const std::vector<double> bp = s.knots(k).breakpoints();
    ne[k] = static_cast<int>(bp.size()) - 1;
    for (int e = 0; e < ne[k]; ++e) {
      const bool own_start = e == 0 || discontinuous_at(s.knots(k), bp[e]);
      if (e > 0 && own_start) u[k].back() = std::nextafter(bp[e], -std::numeric_limits<double>::infinity());
      first[k].push_back(static_cast<int>(u[k].size()) - (own_start ? 0 : 1));
      for (int j = own_start ? 0 : 1; j <= n; ++j)
        u[k].push_back(j == n ? bp[e + 1] : bp[e] + (bp[e + 1] - bp[e]) * j / n);
    }
    nu[k] = static_cast<int>(u[k].size());
  }
  double num_cells = 1;
  for (int k = 0; k < D; ++k) num_cells *= static_cast<double>(ne[k]) * n;
  check_size<D>(nu, path, s.dim() + 6 + extra + field_values, num_cells, 1 << D);
  std::vector<double> x(static_cast<std::size_t>(product<D>(nu)) * s.dim());
  s.eval_grid(u, x);
  const long long base = piece.num_points();
  for_each_index<D>(nu, [&](const std::array<int, D>& i) {
    double param[D];
    for (int k = 0; k < D; ++k) param[k] = u[k][i[k]];
    piece.add_point(x.data() + static_cast<std::size_t>(linear<D>(i, nu)) * s.dim(), s.dim(), extra, param, D);
  });

  std::array<int, D> cells;
  for (int k = 0; k < D; ++k) cells[k] = ne[k] * n;
  static constexpr int kCorner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                        {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for_each_index<D>(cells, [&](const std::array<int, D>& c) {
    std::array<int, D> e, lo;
    for (int k = 0; k < D; ++k) {
      e[k] = c[k] / n;
      lo[k] = first[k][e[k]] + c[k] % n;
    }
    for (int q = 0; q < (1 << D); ++q) {
      std::array<int, D> g;
      for (int k = 0; k < D; ++k) g[k] = lo[k] + kCorner[q][k];
      piece.connectivity.push_back(base + linear<D>(g, nu));
    }
    piece.end_cell(kVtkLinearCell[D - 1], linear<D>(e, ne));
  });
}

template <int D>
void add_bezier(SplinePiece& piece, const TensorSpline<D>& s, int extra, int field_values, const std::string& path) {
  // Per direction: global Bezier node index of each element's first node; shared across continuous joins.
  std::array<std::vector<int>, D> first;
  std::array<std::vector<double>, D> bp;
  std::array<int, D> ne, nn, p;
  for (int k = 0; k < D; ++k) {
    p[k] = s.degree(k);
    require(p[k] >= 1, path + ": Bezier cells need degree >= 1 in every direction, direction " +
                           std::string(1, "uvw"[k]) + " has degree 0 (use sampled output)");
    bp[k] = s.knots(k).breakpoints();
    ne[k] = static_cast<int>(bp[k].size()) - 1;
    int next = 0;
    for (int e = 0; e < ne[k]; ++e) {
      if (e > 0 && discontinuous_at(s.knots(k), bp[k][e])) ++next;
      first[k].push_back(next);
      next += p[k];
    }
    nn[k] = next + 1;
  }
  double num_cells = 1, nodes = 1;
  for (int k = 0; k < D; ++k) {
    num_cells *= ne[k];
    nodes *= p[k] + 1;
  }
  // Bezier nets of all elements (homogeneous), then per point coordinates, parameters, weight and fields.
  check_size<D>(nn, path, s.dim() + D + 7 + extra + 2 * field_values, num_cells,
                static_cast<int>(nodes * (2 + s.dim() + 1)));
  const std::int64_t base = piece.num_points();
  const std::size_t total = static_cast<std::size_t>(product<D>(nn));
  std::vector<double> x(total * s.dim()), w(total), param(total * D);

  const auto elements = bezier_elements(s);
  std::array<int, D> local;
  for (int k = 0; k < D; ++k) local[k] = p[k] + 1;
  const int npe = static_cast<int>(product<D>(local));
  std::vector<std::int64_t> conn(npe);
  const int dim = s.dim();
  for (int l = 0; l < static_cast<int>(elements.size()); ++l) {
    const BezierElement<D>& el = elements[l];
    std::array<int, D> e;
    for (int k = 0, r = l; k < D; ++k) {
      e[k] = r % ne[k];
      r /= ne[k];
    }
    for_each_index<D>(local, [&](const std::array<int, D>& i) {
      std::array<int, D> g;
      for (int k = 0; k < D; ++k) g[k] = first[k][e[k]] + i[k];
      const std::size_t G = static_cast<std::size_t>(linear<D>(g, nn));
      const double* c = el.coefs.data() + static_cast<std::size_t>(linear<D>(i, local)) * el.stride();
      const double wt = el.rational ? c[dim] : 1.0;
      for (int d = 0; d < dim; ++d) x[G * dim + d] = c[d] / wt;
      w[G] = wt;
      piece.rational = piece.rational || wt != 1.0;
      piece.element_nodes.push_back(base + static_cast<std::int64_t>(G));
      for (int k = 0; k < D; ++k)
        param[G * D + k] = el.domain.lo[k] + (el.domain.hi[k] - el.domain.lo[k]) * i[k] / p[k];
      conn[vtk_node_index<D>(i, p)] = base + static_cast<std::int64_t>(G);
    });
    piece.connectivity.insert(piece.connectivity.end(), conn.begin(), conn.end());
    piece.end_cell(kVtkBezierCell[D - 1], linear<D>(e, ne));
    for (int k = 0; k < 3; ++k) piece.degrees.push_back(k < D ? p[k] : 0);
    if (l == 0) piece.element_degrees.assign(p.begin(), p.end());
  }
  for (std::size_t G = 0; G < total; ++G) piece.add_point(x.data() + G * dim, dim, extra, param.data() + G * D, D);
  piece.weights.insert(piece.weights.end(), w.begin(), w.end());
}

template <int D>
void add_control_net(SplinePiece& piece, const TensorSpline<D>& s, int extra) {
  const std::int64_t base = piece.num_points();
  std::array<std::vector<double>, D> greville;
  for (int k = 0; k < D; ++k) greville[k] = s.knots(k).greville();
  const auto n = s.counts();
  std::vector<double> x(s.dim());
  for_each_index<D>(n, [&](const std::array<int, D>& i) {
    const int l = s.linear_index(i);
    s.control_point(l, x.data());
    double param[D];
    for (int k = 0; k < D; ++k) param[k] = greville[k][i[k]];
    piece.add_point(x.data(), s.dim(), extra, param, D);
    for (int k = 0; k < D; ++k) {
      if (i[k] + 1 == n[k]) continue;
      auto j = i;
      ++j[k];
      piece.connectivity.push_back(base + l);
      piece.connectivity.push_back(base + s.linear_index(j));
      piece.end_cell(kVtkLinearCell[0], k);
    }
  });
}

// Bezier mode: the field values sampled at the nodes become the elements' Bezier coefficients. Shared points
// get the same coefficients from every element holding them, since a face's coefficients depend only on the
// values and weights on that face.
template <int D>
std::vector<double> bezier_coefficients(const SplinePiece& piece, const std::vector<double>& at_nodes, int components) {
  Ints<D> p;
  for (int k = 0; k < D; ++k) p[k] = piece.element_degrees[static_cast<std::size_t>(k)];
  BernsteinInterpolation<D> interpolation(p);
  int npe = 1;
  for (int k = 0; k < D; ++k) npe *= p[k] + 1;
  std::vector<double> out(at_nodes.size()), values(static_cast<std::size_t>(npe) * components), w;
  for (std::size_t first = 0; first < piece.element_nodes.size(); first += static_cast<std::size_t>(npe)) {
    const std::int64_t* nodes = piece.element_nodes.data() + first;
    for (int n = 0; n < npe; ++n)
      for (int c = 0; c < components; ++c)
        values[static_cast<std::size_t>(n * components + c)] = at_nodes[static_cast<std::size_t>(nodes[n] * components + c)];
    w.clear();
    if (piece.rational)
      for (int n = 0; n < npe; ++n) w.push_back(piece.weights[static_cast<std::size_t>(nodes[n])]);
    interpolation.apply(values, components, w);
    for (int n = 0; n < npe; ++n)
      for (int c = 0; c < components; ++c)
        out[static_cast<std::size_t>(nodes[n] * components + c)] = values[static_cast<std::size_t>(n * components + c)];
  }
  return out;
}

VtuPiece vtu_piece(const SplinePiece& p, VtkCells mode, bool rational, const std::vector<VtkPointField>& fields, int extra) {
  const bool bezier = mode == VtkCells::bezier;
  VtuPiece v;
  v.num_points = p.num_points();
  v.num_cells = static_cast<std::int64_t>(p.types.size());
  if (bezier && rational) v.point_data_attributes = " RationalWeights=\"RationalWeights\"";
  v.point_data.push_back(VtuDataArray::make("param", 3, p.params));
  if (bezier && rational) v.point_data.push_back(VtuDataArray::make("RationalWeights", 1, p.weights));
  if (extra > 0) v.point_data.push_back(VtuDataArray::make("higher_components", extra, p.higher));
  for (std::size_t f = 0; f < fields.size(); ++f)
    v.point_data.push_back(VtuDataArray::make(fields[f].name, fields[f].components, p.fields[f]));
  if (bezier) v.cell_data_attributes = " HigherOrderDegrees=\"HigherOrderDegrees\"";
  v.cell_data.push_back(VtuDataArray::make(mode == VtkCells::control_net ? "direction" : "element", 1, p.element));
  if (bezier) v.cell_data.push_back(VtuDataArray::make("HigherOrderDegrees", 3, p.degrees));
  v.points = VtuDataArray::make("", 3, p.points);
  v.connectivity = VtuDataArray::make("connectivity", 1, p.connectivity);
  v.offsets = VtuDataArray::make("offsets", 1, p.offsets);
  v.types = VtuDataArray::make("types", 1, p.types);
  return v;
}

void validate(const std::string& path, VtkCells mode, int samples, const std::vector<VtkPointField>& fields) {
  require(mode != VtkCells::sampled || samples >= 1,
          path + ": samples_per_element must be >= 1, got " + std::to_string(samples));
  validate_fields(path, "point field", fields, kReservedNames);
}

}  // namespace

void write_vtu(const std::string& path, const std::vector<AnySpline>& objects, const VtkOptions& opts,
               const std::vector<VtkPointField>& fields) {
  require(!objects.empty(), path + ": nothing to write (no objects)");
  const VtkCells mode = opts.cells;
  validate(path, mode, opts.samples_per_element, fields);
  int extra = 0, field_values = 0;
  for (const VtkPointField& f : fields) field_values += f.components;
  for (const auto& o : objects) extra = std::max(extra, std::visit([](const auto& s) { return s.dim(); }, o) - 3);

  std::vector<SplinePiece> pieces(objects.size());
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const std::string where = objects.size() > 1 ? path + ": object " + std::to_string(i + 1) : path;
    std::visit(
        [&](const auto& s) {
          constexpr int D = std::decay_t<decltype(s)>::kDim;
          require(s.dim() >= 1, where + ": cannot write an empty spline (no control points)");
          SplinePiece& piece = pieces[i];
          switch (mode) {
            case VtkCells::sampled:
              add_sampled(piece, s, opts.samples_per_element, extra, field_values, where);
              break;
            case VtkCells::bezier:
              add_bezier(piece, s, extra, field_values, where);
              break;
            case VtkCells::control_net:
              add_control_net(piece, s, extra);
              break;
          }
          for (const VtkPointField& field : fields) {
            std::vector<double>& values = piece.fields.emplace_back(static_cast<std::size_t>(piece.num_points()) *
                                                                    static_cast<std::size_t>(field.components));
            for (std::int64_t q = 0; q < piece.num_points(); ++q)
              field.value(static_cast<int>(i), std::span<const double>(piece.params.data() + 3 * q, D),
                          std::span<double>(values.data() + q * field.components, field.components));
            if (mode == VtkCells::bezier) values = bezier_coefficients<D>(piece, values, field.components);
          }
        },
        objects[i]);
  }

  // RationalWeights in every piece or none, so ParaView merges the pieces into one data set.
  bool rational = false;
  for (const SplinePiece& p : pieces) rational = rational || p.rational;
  std::vector<VtuPiece> out;
  for (SplinePiece& p : pieces) {
    out.push_back(vtu_piece(p, mode, rational, fields, extra));
    p = SplinePiece{};  // the compressed copy is all that is needed from here on
  }
  write_vtu_file(path, out);
}

void write_vtu(const std::string& path, const AnySpline& s, const VtkOptions& opts,
               const std::vector<VtkPointField>& fields) {
  write_vtu(path, std::vector<AnySpline>{s}, opts, fields);
}

}  // namespace trivar::io
