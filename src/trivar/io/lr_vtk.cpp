#include "trivar/io/lr_vtk.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <cstdint>
#include <type_traits>

#include "trivar/core/error.hpp"
#include "trivar/core/memory_budget.hpp"
#include "trivar/core/number_format.hpp"
#include "trivar/io/vtk_cell_order.hpp"
#include "trivar/io/vtu_fields.hpp"
#include "trivar/io/vtu_file.hpp"
#include "trivar/lr/lr_bezier_extraction.hpp"
#include "trivar/spline/bernstein_interpolation.hpp"

namespace trivar::io {

namespace {

constexpr std::array<const char*, 3> kReservedPointNames = {"param", "higher_components", "RationalWeights"};
constexpr std::array<const char*, 3> kReservedCellNames = {"element", "support", "HigherOrderDegrees"};

struct Piece {
  std::vector<double> points, params, higher, weights;
  std::vector<std::int64_t> connectivity, offsets;
  std::vector<std::uint8_t> types;
  std::vector<std::int32_t> element, support, degrees;
  std::vector<std::vector<double>> point_fields, cell_fields;
  bool rational = false;
  std::size_t num_points() const { return points.size() / 3; }
};

// VTK corner order of the unit square / cube as (i, j, k) bits: counter-clockwise bottom, then top.
constexpr int kCorners[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};

// Calls f(i) for every multi-index 0 <= i_k <= n_k, first index fastest.
template <int D, class F>
void for_each_node(const Ints<D>& n, F&& f) {
  Ints<D> i{};
  for (;;) {
    f(i);
    int k = 0;
    for (; k < D; ++k) {
      if (++i[k] <= n[k]) break;
      i[k] = 0;
    }
    if (k == D) return;
  }
}

template <int D>
std::int64_t node_linear(const Ints<D>& i, const Ints<D>& n) {
  std::int64_t l = 0;
  for (int k = D - 1; k >= 0; --k) l = l * (n[k] + 1) + i[k];
  return l;
}

// Linear cells of an element sampled on an n^D grid (points base + node_linear).
template <int D>
void add_linear_cells(Piece& p, const Ints<D>& n, std::int64_t base) {
  Ints<D> last;
  for (int k = 0; k < D; ++k) last[k] = n[k] - 1;
  for_each_node<D>(last, [&](const Ints<D>& c) {
    for (int v = 0; v < (1 << D); ++v) {
      Ints<D> i = c;
      for (int k = 0; k < D; ++k) i[k] += kCorners[v][k];
      p.connectivity.push_back(base + node_linear<D>(i, n));
    }
    p.offsets.push_back(static_cast<std::int64_t>(p.connectivity.size()));
    p.types.push_back(kVtkLinearCell[D - 1]);
  });
}

// What the writer reads of a locally refined object, element by element: the element's box, its Bezier net
// (u fastest, stride dim + rational) and the number of functions non-zero on it.
template <int D>
struct LRSource {
  const LRSpline<D>& s;
  int degree(int k) const { return s.degree(k); }
  int num_elements() const { return s.num_elements(); }
  Box<D> box(int e) const { return s.element(e); }
  int support(int e) const { return static_cast<int>(s.element_support(e).size()); }
  void net(int e, std::vector<double>& out) const {
    out = bezier_element<D>(s.degrees(), s.basis_functions(), s.element_support(e), s.element(e), s.dim(), s.is_rational()).coefs;
  }
};

template <int D>
struct HierarchicalSource {
  const HierarchicalSpline<D>& s;
  int degree(int k) const { return s.space().degree(k); }
  int num_elements() const { return s.space().num_elements(); }
  Box<D> box(int e) const { return s.space().element_box(e); }
  int support(int e) const { return static_cast<int>(s.space().element_operator(e).ids.size()); }
  void net(int e, std::vector<double>& out) const {
    const auto n = s.evaluator().net(e);
    out.assign(n.begin(), n.end());
  }
};

template <int D, template <int> class Source, class Spline>
Piece build_piece(const Spline& s, int piece, const LRVtkOptions& opts,
                  const std::vector<VtkPointField>& point_fields, const std::vector<LRVtkCellField>& cell_fields,
                  const std::string& where) {
  Piece p;
  p.point_fields.resize(point_fields.size());
  p.cell_fields.resize(cell_fields.size());
  std::vector<double> value;
  const int dim = s.dim();
  const bool bezier = opts.cells == LRVtkCells::bezier, mesh = opts.cells == LRVtkCells::parametric_mesh;
  // Nodes per element: the Bezier nodes, the sample grid or the corners.
  const Source<D> source{s};
  Ints<D> n;
  for (int k = 0; k < D; ++k) {
    n[k] = bezier ? source.degree(k) : mesh ? 1 : opts.samples_per_element;
    require(n[k] >= 1, where + ": Bezier cells need degree >= 1 in every direction, direction " +
                           std::string(1, "uvw"[k]) + " has degree 0 (use sampled output)");
  }
  std::optional<BernsteinInterpolation<D>> interpolation;
  if (bezier) interpolation.emplace(n);
  std::int32_t nodes = 1;
  for (int k = 0; k < D; ++k) nodes *= n[k] + 1;
  // Elements do not share points: per point coordinates, parameters, weight and fields, per cell its corners.
  int field_values = 0;
  for (const VtkPointField& f : point_fields) field_values += f.components;
  const auto run = opts.runs.empty() ? std::pair{opts.first_element, opts.last_element} : opts.runs[static_cast<std::size_t>(piece)];
  const int first_element = run.first, last_element = run.second < 0 ? source.num_elements() : run.second;
  require(0 <= first_element && first_element <= last_element && last_element <= source.num_elements(),
          where + ": element run [" + std::to_string(first_element) + ", " + std::to_string(last_element) +
              ") outside the " + std::to_string(source.num_elements()) + " elements");
  const double points = static_cast<double>(last_element - first_element) * nodes;
  require_memory(8.0 * points * (7 + std::max(dim - 3, 0) + field_values + 2),
                 where + ": VTU output of " + format_number(points) + " points");
  std::vector<std::int64_t> conn(static_cast<std::size_t>(nodes));
  std::vector<double> x(static_cast<std::size_t>(dim)), element_weights, net;
  const int stride = dim + (s.is_rational() ? 1 : 0);
  for (int e = first_element; e < last_element; ++e) {
    const Box<D> b = source.box(e);
    const auto base = static_cast<std::int64_t>(p.num_points());
    if (bezier) {
      source.net(e, net);
      element_weights.clear();
    }
    for_each_node<D>(n, [&](const Ints<D>& i) {
      Param<D> u, at;
      for (int k = 0; k < D; ++k) {
        u[k] = i[k] == n[k] ? b.hi[k] : b.lo[k] + (b.hi[k] - b.lo[k]) * i[k] / n[k];
        at[k] = i[k] == n[k] && b.hi[k] < s.domain().hi[k] ? std::nextafter(b.hi[k], b.lo[k]) : u[k];
      }
      for (int k = 0; k < 3; ++k) p.params.push_back(k < D ? u[k] : 0.0);
      if (mesh) {
        for (int k = 0; k < 3; ++k) p.points.push_back(k < D ? u[k] : 0.0);
      } else {
        if (bezier) {
          const double* c = net.data() + static_cast<std::size_t>(node_linear<D>(i, n)) * stride;
          const double w = s.is_rational() ? c[dim] : 1.0;
          for (int d = 0; d < dim; ++d) x[static_cast<std::size_t>(d)] = c[d] / w;
          p.weights.push_back(w);
          element_weights.push_back(w);
          p.rational = p.rational || w != 1.0;
          conn[static_cast<std::size_t>(vtk_node_index<D>(i, n))] = base + node_linear<D>(i, n);
        } else {
          s.eval(at, x.data());
        }
        for (int k = 0; k < 3; ++k) p.points.push_back(k < dim ? x[static_cast<std::size_t>(k)] : 0.0);
        for (int k = 3; k < dim; ++k) p.higher.push_back(x[static_cast<std::size_t>(k)]);
      }
      for (std::size_t f = 0; f < point_fields.size(); ++f) {
        value.resize(static_cast<std::size_t>(point_fields[f].components));
        point_fields[f].value(piece, at, value);
        p.point_fields[f].insert(p.point_fields[f].end(), value.begin(), value.end());
      }
    });
    const std::size_t first = p.types.size();
    if (bezier) {
      p.connectivity.insert(p.connectivity.end(), conn.begin(), conn.end());
      p.offsets.push_back(static_cast<std::int64_t>(p.connectivity.size()));
      p.types.push_back(kVtkBezierCell[D - 1]);
      for (int k = 0; k < 3; ++k) p.degrees.push_back(k < D ? n[k] : 0);
      // The field values at this element's nodes become its Bezier coefficients (points are not shared).
      for (std::size_t f = 0; f < point_fields.size(); ++f) {
        const int c = point_fields[f].components;
        std::span<double> values(p.point_fields[f].data() + base * c, static_cast<std::size_t>(nodes * c));
        interpolation->apply(values, c, s.is_rational() ? std::span<const double>(element_weights) : std::span<const double>());
      }
    } else {
      add_linear_cells<D>(p, n, base);
    }
    const int support = source.support(e);
    for (std::size_t c = first; c < p.types.size(); ++c) {
      p.element.push_back(e);
      p.support.push_back(support);
    }
    for (std::size_t f = 0; f < cell_fields.size(); ++f) {
      value.resize(static_cast<std::size_t>(cell_fields[f].components));
      cell_fields[f].value(piece, e, value);
      for (std::size_t c = first; c < p.types.size(); ++c)
        p.cell_fields[f].insert(p.cell_fields[f].end(), value.begin(), value.end());
    }
  }
  if (mesh || dim <= 3) p.higher.clear();
  return p;
}

VtuPiece vtu_piece(const Piece& p, bool bezier, bool rational, const std::vector<VtkPointField>& point_fields,
                   const std::vector<LRVtkCellField>& cell_fields) {
  VtuPiece v;
  v.num_points = static_cast<std::int64_t>(p.num_points());
  v.num_cells = static_cast<std::int64_t>(p.types.size());
  v.point_data.push_back(VtuDataArray::make("param", 3, p.params));
  if (bezier && rational) {
    v.point_data_attributes = " RationalWeights=\"RationalWeights\"";
    v.point_data.push_back(VtuDataArray::make("RationalWeights", 1, p.weights));
  }
  if (!p.higher.empty())
    v.point_data.push_back(
        VtuDataArray::make("higher_components", static_cast<int>(p.higher.size() / p.num_points()), p.higher));
  for (std::size_t f = 0; f < point_fields.size(); ++f)
    v.point_data.push_back(VtuDataArray::make(point_fields[f].name, point_fields[f].components, p.point_fields[f]));
  v.cell_data.push_back(VtuDataArray::make("element", 1, p.element));
  v.cell_data.push_back(VtuDataArray::make("support", 1, p.support));
  if (bezier) {
    v.cell_data_attributes = " HigherOrderDegrees=\"HigherOrderDegrees\"";
    v.cell_data.push_back(VtuDataArray::make("HigherOrderDegrees", 3, p.degrees));
  }
  for (std::size_t f = 0; f < cell_fields.size(); ++f)
    v.cell_data.push_back(VtuDataArray::make(cell_fields[f].name, cell_fields[f].components, p.cell_fields[f]));
  v.points = VtuDataArray::make("", 3, p.points);
  v.connectivity = VtuDataArray::make("connectivity", 1, p.connectivity);
  v.offsets = VtuDataArray::make("offsets", 1, p.offsets);
  v.types = VtuDataArray::make("types", 1, p.types);
  return v;
}

}  // namespace

namespace {

template <class T>
constexpr int kParametricDimension = 0;
template <int D>
constexpr int kParametricDimension<LRSpline<D>> = D;
template <int D>
constexpr int kParametricDimension<HierarchicalSpline<D>> = D;

template <template <int> class Source, class Any>
void write_pieces(const std::string& path, const std::vector<Any>& objects, const LRVtkOptions& opts,
                  const std::vector<VtkPointField>& point_fields, const std::vector<LRVtkCellField>& cell_fields) {
  require(!objects.empty(), path + ": nothing to write (no objects)");
  require(opts.cells != LRVtkCells::sampled || opts.samples_per_element >= 1,
          path + ": samples per element must be at least 1, got " + std::to_string(opts.samples_per_element));
  require(opts.runs.empty() || opts.runs.size() == objects.size(), path + ": " + std::to_string(opts.runs.size()) +
                                                                      " element runs for " + std::to_string(objects.size()) + " objects");
  validate_fields(path, "point field", point_fields, kReservedPointNames);
  validate_fields(path, "cell field", cell_fields, kReservedCellNames);
  std::vector<Piece> pieces;
  pieces.reserve(objects.size());
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const std::string where = objects.size() > 1 ? path + ": object " + std::to_string(i + 1) : path;
    pieces.push_back(std::visit(
        [&](const auto& o) {
          constexpr int D = kParametricDimension<std::decay_t<decltype(o)>>;
          return build_piece<D, Source>(o, static_cast<int>(i), opts, point_fields, cell_fields, where);
        },
        objects[i]));
  }
  // RationalWeights in every piece or none, so ParaView merges the pieces into one data set.
  bool rational = false;
  for (const Piece& p : pieces) rational = rational || p.rational;
  std::vector<VtuPiece> out;
  for (Piece& p : pieces) {
    out.push_back(vtu_piece(p, opts.cells == LRVtkCells::bezier, rational, point_fields, cell_fields));
    p = Piece{};
  }
  write_vtu_file(path, out);
}

}  // namespace

void write_lr_vtu(const std::string& path, const std::vector<AnyLRSpline>& objects, const LRVtkOptions& opts,
                  const std::vector<VtkPointField>& point_fields, const std::vector<LRVtkCellField>& cell_fields) {
  write_pieces<LRSource>(path, objects, opts, point_fields, cell_fields);
}

void write_lr_vtu(const std::string& path, const AnyLRSpline& s, const LRVtkOptions& opts,
                  const std::vector<VtkPointField>& point_fields, const std::vector<LRVtkCellField>& cell_fields) {
  write_lr_vtu(path, std::vector<AnyLRSpline>{s}, opts, point_fields, cell_fields);
}

void write_hierarchical_vtu(const std::string& path, const std::vector<AnyHierarchicalSpline>& objects,
                            const LRVtkOptions& opts, const std::vector<VtkPointField>& point_fields,
                            const std::vector<LRVtkCellField>& cell_fields) {
  write_pieces<HierarchicalSource>(path, objects, opts, point_fields, cell_fields);
}

}  // namespace trivar::io
