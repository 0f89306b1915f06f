#include "trivar/io/t_spline_vtk.hpp"

#include <cstdint>
#include <ostream>

#include "trivar/core/atomic_file.hpp"
#include "trivar/core/error.hpp"
#include "trivar/core/number_format.hpp"
#include "trivar/io/vtk_cell_order.hpp"
#include "trivar/io/vtu_file.hpp"

namespace trivar::io {

void write_t_spline_vtu(const std::string& path, const TSplineSurface& surface) {
  const auto& nets = surface.bezier_elements();
  const int p = surface.degrees()[0], q = surface.degrees()[1];
  const int per = (p + 1) * (q + 1);
  std::vector<double> xyz, weights;
  std::vector<std::int64_t> conn, offsets, degrees, element, functions;
  std::vector<std::uint8_t> types;
  for (std::size_t e = 0; e < nets.size(); ++e) {
    const std::size_t base = weights.size();
    xyz.resize(xyz.size() + 3 * static_cast<std::size_t>(per));
    weights.resize(weights.size() + static_cast<std::size_t>(per));
    for (int j = 0; j <= q; ++j)
      for (int i = 0; i <= p; ++i) {
        const double* c = nets[e].coefs.data() + 4 * static_cast<std::size_t>(i + (p + 1) * j);
        const std::size_t at = base + static_cast<std::size_t>(vtk_node_index<2>({i, j}, {p, q}));
        for (int d = 0; d < 3; ++d) xyz[3 * at + static_cast<std::size_t>(d)] = c[d] / c[3];
        weights[at] = c[3];
      }
    for (int k = 0; k < per; ++k) conn.push_back(static_cast<std::int64_t>(base) + k);
    offsets.push_back(static_cast<std::int64_t>(conn.size()));
    types.push_back(kVtkBezierCell[1]);
    degrees.insert(degrees.end(), {p, q, 0});
    element.push_back(static_cast<std::int64_t>(e));
    functions.push_back(static_cast<std::int64_t>(surface.element_supports()[static_cast<int>(e)].size()));
  }
  VtuPiece v;
  v.num_points = static_cast<std::int64_t>(weights.size());
  v.num_cells = static_cast<std::int64_t>(nets.size());
  v.points = VtuDataArray::make("", 3, xyz);
  v.connectivity = VtuDataArray::make("connectivity", 1, conn);
  v.offsets = VtuDataArray::make("offsets", 1, offsets);
  v.types = VtuDataArray::make("types", 1, types);
  v.point_data_attributes = " RationalWeights=\"RationalWeights\"";
  v.point_data.push_back(VtuDataArray::make("RationalWeights", 1, weights));
  v.cell_data_attributes = " HigherOrderDegrees=\"HigherOrderDegrees\"";
  v.cell_data.push_back(VtuDataArray::make("HigherOrderDegrees", 3, degrees));
  v.cell_data.push_back(VtuDataArray::make("element", 1, element));
  v.cell_data.push_back(VtuDataArray::make("blending_functions", 1, functions));
  write_vtu_file(path, {std::move(v)});
}

void write_triangulation_vtu(const std::string& path, const TSplineTriangulation& m) {
  std::vector<double> xyz, st;
  for (const auto& x : m.points) xyz.insert(xyz.end(), x.begin(), x.end());
  for (const auto& u : m.params) st.insert(st.end(), u.begin(), u.end());
  std::vector<std::int64_t> conn, offsets;
  for (const auto& t : m.triangles) {
    conn.insert(conn.end(), t.begin(), t.end());
    offsets.push_back(static_cast<std::int64_t>(conn.size()));
  }
  VtuPiece v;
  v.num_points = static_cast<std::int64_t>(m.points.size());
  v.num_cells = static_cast<std::int64_t>(m.triangles.size());
  v.points = VtuDataArray::make("", 3, xyz);
  v.connectivity = VtuDataArray::make("connectivity", 1, conn);
  v.offsets = VtuDataArray::make("offsets", 1, offsets);
  v.types = VtuDataArray::make("types", 1, std::vector<std::uint8_t>(m.triangles.size(), kVtkTriangle));
  v.point_data.push_back(VtuDataArray::make("param", 2, st));
  write_vtu_file(path, {std::move(v)});
}

void write_triangulation_obj(const std::string& path, const TSplineTriangulation& m) {
  require(!m.triangles.empty(), "OBJ: no triangle to write to " + path);
  write_file_atomically(path, [&](std::ostream& os) {
    os << "# trivar T-spline tessellation: " << m.points.size() << " vertices, " << m.triangles.size() << " triangles\n";
    for (const auto& x : m.points) os << "v " << format_number(x[0]) << ' ' << format_number(x[1]) << ' ' << format_number(x[2]) << '\n';
    for (const auto& u : m.params) os << "vt " << format_number(u[0]) << ' ' << format_number(u[1]) << '\n';
    for (const auto& t : m.triangles)
      os << "f " << t[0] + 1 << '/' << t[0] + 1 << ' ' << t[1] + 1 << '/' << t[1] + 1 << ' ' << t[2] + 1 << '/' << t[2] + 1 << '\n';
  });
}

}  // namespace trivar::io
