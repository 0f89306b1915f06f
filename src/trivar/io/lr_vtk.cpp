#include "trivar/io/lr_vtk.hpp"

#include <cmath>
#include <cstdint>
#include <ostream>
#include <type_traits>

#include "trivar/core/atomic_file.hpp"
#include "trivar/core/error.hpp"
#include "trivar/core/number_format.hpp"
#include "trivar/io/vtu_data_array.hpp"
#include "trivar/io/vtu_fields.hpp"

namespace trivar::io {

namespace {

constexpr std::uint8_t kVtkQuad = 9;
constexpr std::uint8_t kVtkHexahedron = 12;
constexpr std::array<const char*, 2> kReservedPointNames = {"param", "higher_components"};
constexpr std::array<const char*, 2> kReservedCellNames = {"element", "support"};

struct Piece {
  std::vector<double> points, params, higher;
  std::vector<std::int64_t> connectivity, offsets;
  std::vector<std::uint8_t> types;
  std::vector<int> element, support;
  std::vector<std::vector<double>> point_fields, cell_fields;
  std::size_t num_points() const { return points.size() / 3; }
};

// VTK corner order of the unit square / cube as (i, j, k) bits: counter-clockwise bottom, then top.
constexpr int kCorners[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};

template <int D>
void add_cells(Piece& p, const std::array<int, D>& n, std::int64_t base, int element, int support) {
  const auto index = [&](const std::array<int, D>& i) {
    std::int64_t l = 0;
    for (int k = D - 1; k >= 0; --k) l = l * (n[k] + 1) + i[k];
    return base + l;
  };
  std::array<int, D> c{};
  for (;;) {
    for (int v = 0; v < (1 << D); ++v) {
      std::array<int, D> i = c;
      for (int k = 0; k < D; ++k) i[k] += kCorners[v][k];
      p.connectivity.push_back(index(i));
    }
    p.offsets.push_back(static_cast<std::int64_t>(p.connectivity.size()));
    p.types.push_back(D == 2 ? kVtkQuad : kVtkHexahedron);
    p.element.push_back(element);
    p.support.push_back(support);
    int k = 0;
    for (; k < D; ++k) {
      if (++c[k] < n[k]) break;
      c[k] = 0;
    }
    if (k == D) return;
  }
}

template <int D>
Piece build_piece(const LRSpline<D>& s, int piece, const LRVtkOptions& opts,
                  const std::vector<VtkPointField>& point_fields, const std::vector<LRVtkCellField>& cell_fields) {
  Piece p;
  p.point_fields.resize(point_fields.size());
  p.cell_fields.resize(cell_fields.size());
  std::vector<double> value;
  const int dim = s.dim();
  const int extra = dim > 3 ? dim - 3 : 0;
  const int n = opts.parametric_mesh ? 1 : opts.samples_per_element;
  std::array<int, D> counts;
  counts.fill(n);
  std::vector<double> x(static_cast<std::size_t>(dim));
  for (int e = 0; e < s.num_elements(); ++e) {
    const Box<D>& b = s.element(e);
    const auto base = static_cast<std::int64_t>(p.num_points());
    std::array<int, D> i{};
    for (;;) {
      Param<D> u, at;
      for (int k = 0; k < D; ++k) {
        u[k] = i[k] == n ? b.hi[k] : b.lo[k] + (b.hi[k] - b.lo[k]) * i[k] / n;
        at[k] = i[k] == n && b.hi[k] < s.domain().hi[k] ? std::nextafter(b.hi[k], b.lo[k]) : u[k];
      }
      for (int k = 0; k < 3; ++k) p.params.push_back(k < D ? u[k] : 0.0);
      if (opts.parametric_mesh) {
        for (int k = 0; k < 3; ++k) p.points.push_back(k < D ? u[k] : 0.0);
      } else {
        s.eval(at, x.data());
        for (int k = 0; k < 3; ++k) p.points.push_back(k < dim ? x[static_cast<std::size_t>(k)] : 0.0);
        for (int k = 3; k < dim; ++k) p.higher.push_back(x[static_cast<std::size_t>(k)]);
      }
      for (std::size_t f = 0; f < point_fields.size(); ++f) {
        value.resize(static_cast<std::size_t>(point_fields[f].components));
        point_fields[f].value(piece, at, value);
        p.point_fields[f].insert(p.point_fields[f].end(), value.begin(), value.end());
      }
      int k = 0;
      for (; k < D; ++k) {
        if (++i[k] <= n) break;
        i[k] = 0;
      }
      if (k == D) break;
    }
    const std::size_t first = p.types.size();
    add_cells<D>(p, counts, base, e, static_cast<int>(s.element_support(e).size()));
    for (std::size_t f = 0; f < cell_fields.size(); ++f) {
      value.resize(static_cast<std::size_t>(cell_fields[f].components));
      cell_fields[f].value(piece, e, value);
      for (std::size_t c = first; c < p.types.size(); ++c)
        p.cell_fields[f].insert(p.cell_fields[f].end(), value.begin(), value.end());
    }
  }
  if (opts.parametric_mesh || extra == 0) p.higher.clear();
  return p;
}

void write_piece(std::ostream& os, const Piece& p, const std::vector<VtkPointField>& point_fields,
                 const std::vector<LRVtkCellField>& cell_fields) {
  os << "    <Piece NumberOfPoints=\"" << p.num_points() << "\" NumberOfCells=\"" << p.types.size() << "\">\n";
  os << "      <PointData>\n";
  write_data_array(os, "Float64", "param", 3, p.params);
  if (!p.higher.empty())
    write_data_array(os, "Float64", "higher_components", static_cast<int>(p.higher.size() / p.num_points()), p.higher);
  for (std::size_t f = 0; f < point_fields.size(); ++f)
    write_data_array(os, "Float64", point_fields[f].name, point_fields[f].components, p.point_fields[f]);
  os << "      </PointData>\n      <CellData>\n";
  write_data_array(os, "Int32", "element", 1, p.element);
  write_data_array(os, "Int32", "support", 1, p.support);
  for (std::size_t f = 0; f < cell_fields.size(); ++f)
    write_data_array(os, "Float64", cell_fields[f].name, cell_fields[f].components, p.cell_fields[f]);
  os << "      </CellData>\n      <Points>\n";
  write_data_array(os, "Float64", "", 3, p.points);
  os << "      </Points>\n      <Cells>\n";
  write_data_array(os, "Int64", "connectivity", 1, p.connectivity);
  write_data_array(os, "Int64", "offsets", 1, p.offsets);
  write_data_array(os, "UInt8", "types", 1, p.types);
  os << "      </Cells>\n    </Piece>\n";
}

}  // namespace

void write_lr_vtu(const std::string& path, const std::vector<AnyLRSpline>& objects, const LRVtkOptions& opts,
                  const std::vector<VtkPointField>& point_fields, const std::vector<LRVtkCellField>& cell_fields) {
  require(!objects.empty(), path + ": nothing to write (no objects)");
  require(opts.samples_per_element >= 1,
          path + ": samples per element must be at least 1, got " + std::to_string(opts.samples_per_element));
  validate_fields(path, "point field", point_fields, kReservedPointNames);
  validate_fields(path, "cell field", cell_fields, kReservedCellNames);
  std::vector<Piece> pieces;
  pieces.reserve(objects.size());
  for (std::size_t i = 0; i < objects.size(); ++i)
    pieces.push_back(std::visit(
        [&](const auto& lr) { return build_piece(lr, static_cast<int>(i), opts, point_fields, cell_fields); },
        objects[i]));
  write_file_atomically(path, [&](std::ostream& os) {
    os << "<?xml version=\"1.0\"?>\n"
          "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
          "  <UnstructuredGrid>\n";
    for (const Piece& p : pieces) write_piece(os, p, point_fields, cell_fields);
    os << "  </UnstructuredGrid>\n</VTKFile>\n";
  });
}

void write_lr_vtu(const std::string& path, const AnyLRSpline& s, const LRVtkOptions& opts,
                  const std::vector<VtkPointField>& point_fields, const std::vector<LRVtkCellField>& cell_fields) {
  write_lr_vtu(path, std::vector<AnyLRSpline>{s}, opts, point_fields, cell_fields);
}

}  // namespace trivar::io
