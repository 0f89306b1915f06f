// VModel: V-models (cells of trivariates with attributes, glued into a topology), their primitives, the
// watertight boundary tessellation and the slicer's layers, as NumPy arrays.
#include <pybind11/eigen.h>

#include "bindings.hpp"
#include "trivar/am/dithering.hpp"
#include "trivar/am/layer_slicer.hpp"
#include "trivar/am/slicer.hpp"
#include "trivar/core/memory_budget.hpp"
#include "trivar/model/ball.hpp"
#include "trivar/model/cone.hpp"
#include "trivar/model/cylinder.hpp"
#include "trivar/model/model_tessellation.hpp"
#include "trivar/model/primitives.hpp"
#include "trivar/model/torus.hpp"
#include "trivar/model/trimmed_solid.hpp"
#include "trivar/model/trimmed_tessellation.hpp"
#include "trivar/model/vmodel.hpp"

namespace trivar::python {

namespace {

py::object namespace_of(py::kwargs kw) { return py::module_::import("types").attr("SimpleNamespace")(**kw); }

VModel glued(const CellComplex& cells) {
  VModel m;
  for (const SplineVolume& c : cells) m.add_cell(VCell(c));
  m.glue();
  return m;
}

std::vector<int> cell_list(const VModel& m, const std::optional<std::vector<int>>& cells) {
  if (cells) {
    for (int c : *cells) require(c >= 0 && c < m.num_cells(), "cells: no cell " + std::to_string(c));
    return *cells;
  }
  std::vector<int> all(static_cast<std::size_t>(m.num_cells()));
  for (int i = 0; i < m.num_cells(); ++i) all[static_cast<std::size_t>(i)] = i;
  return all;
}

void set_attribute(VModel& m, const std::string& name, const std::optional<std::vector<double>>& value,
                   const std::optional<std::vector<std::string>>& expression, const std::optional<SplineVolume>& field,
                   const std::string& space, const std::optional<std::vector<int>>& cells) {
  require(int(value.has_value()) + int(expression.has_value()) + int(field.has_value()) == 1,
          "set_attribute: give exactly one of value, expression or field");
  require(space == "model" || space == "parametric", "set_attribute: space is model or parametric, got " + space);
  const Attribute a = value        ? Attribute::constant(*value)
                      : expression ? Attribute::expression(*expression, space == "model" ? Attribute::Space::model
                                                                                         : Attribute::Space::parametric)
                                   : Attribute::field(*field);
  for (int c : cell_list(m, cells)) m.cell(c).set_attribute(name, a);
}

py::array attribute_values(const VModel& m, int cell, const std::string& name, const Array& u) {
  require(cell >= 0 && cell < m.num_cells(), "attribute: no cell " + std::to_string(cell));
  const Attribute& a = m.cell(cell).attribute(name);
  bool single = false;
  const auto params = params_of<3>(u, single);
  auto out = new_array({static_cast<py::ssize_t>(params.size()), a.components()});
  double* o = out.mutable_data();
  {
    py::gil_scoped_release release;
    for (std::size_t i = 0; i < params.size(); ++i)
      a.eval(m.cell(cell).geometry(), params[i], o + i * static_cast<std::size_t>(a.components()));
  }
  if (single) return out.attr("reshape")(a.components());
  return out;
}

py::object tessellate(const VModel& m, double tolerance) {
  ModelTessellation t;
  {
    py::gil_scoped_release release;
    t = boundary_mesh(m, tolerance);
  }
  const auto nv = static_cast<py::ssize_t>(t.mesh.vertices.size());
  const auto nt = static_cast<py::ssize_t>(t.mesh.triangles.size());
  py::array_t<double> vertices({nv, py::ssize_t{3}}, nv ? &t.mesh.vertices[0][0] : nullptr);
  py::array_t<int> triangles({nt, py::ssize_t{3}}, nt ? &t.mesh.triangles[0][0] : nullptr);
  py::array_t<int> cell(nv, t.cell.data());
  py::array_t<double> params({nv, py::ssize_t{3}}, nv ? &t.param[0][0] : nullptr);
  return namespace_of(py::dict(py::arg("vertices") = vertices, py::arg("triangles") = triangles, py::arg("cell") = cell,
                               py::arg("params") = params, py::arg("watertight") = is_watertight(t.mesh),
                               py::arg("area") = surface_area(t.mesh), py::arg("volume") = enclosed_volume(t.mesh)));
}

py::object slice(const VModel& m, double layer_thickness, const std::vector<double>& dpi,
                 const std::optional<std::vector<double>>& z_range, const std::optional<std::string>& material,
                 const std::string& dither, int threads) {
  require(dpi.size() == 1 || dpi.size() == 2, "slice: dpi is one value or (x, y)");
  require(dither == "error-diffusion" || dither == "ordered" || dither == "none",
          "slice: dither is error-diffusion, ordered or none, got " + dither);
  am::SliceOptions o;
  o.layer_thickness = layer_thickness;
  o.dpi_x = dpi[0];
  o.dpi_y = dpi.back();
  if (z_range) {
    require(z_range->size() == 2, "slice: z_range is (z0, z1)");
    o.z_range = std::array<double, 2>{(*z_range)[0], (*z_range)[1]};
  }
  o.material_attribute = material;
  o.threads = threads;
  // Every layer is returned in memory: the library's layers and the arrays made from them (cell index, float
  // fractions per material, a label).
  const am::SliceGrid g = am::slice_grid(m, o);
  const double channels = m.materials().empty() ? 1.0 : m.materials().size();
  require_memory(2.0 * static_cast<double>(g.layers) * static_cast<double>(g.pixels()) * (4.0 + 4.0 * channels + 1.0),
                 "slicing " + std::to_string(g.layers) + " layers of " + std::to_string(g.width) + " x " +
                     std::to_string(g.height) + " pixels into arrays");
  am::SliceSummary summary;
  std::vector<am::SliceLayer> layers;
  {
    py::gil_scoped_release release;
    layers = am::slice_model(m, o, &summary);
  }
  const auto L = static_cast<py::ssize_t>(layers.size());
  const py::ssize_t H = summary.height, W = summary.width;
  const py::ssize_t C = layers.empty() ? 1 : layers.front().fractions.channels();
  py::array_t<int> cell({L, H, W});
  py::array_t<float> fractions({L, H, W, C});
  py::array_t<std::uint8_t> labels({L, H, W});
  auto z = new_array({L});
  {
    py::gil_scoped_release release;
    for (std::size_t k = 0; k < layers.size(); ++k) {
      const am::SliceLayer& layer = layers[k];
      z.mutable_data()[k] = layer.z;
      std::copy(layer.cell.begin(), layer.cell.end(), cell.mutable_data() + k * static_cast<std::size_t>(H * W));
      const auto& f = layer.fractions.data();
      std::copy(f.begin(), f.end(), fractions.mutable_data() + k * static_cast<std::size_t>(H * W * C));
      if (dither != "none") {
        const LabelImage l =
            am::dither(layer.fractions,
                       {.method = dither == "ordered" ? am::DitherMethod::ordered : am::DitherMethod::error_diffusion});
        std::copy(l.data().begin(), l.data().end(), labels.mutable_data() + k * static_cast<std::size_t>(H * W));
      }
    }
  }
  py::dict d(py::arg("z") = z, py::arg("cell") = cell, py::arg("fractions") = fractions,
             py::arg("pixel_size") = py::make_tuple(g.dx, g.dy), py::arg("origin") = py::make_tuple(g.x0, g.y0),
             py::arg("inside_pixels") = summary.inside_pixels,
             py::arg("full_solve_percent") = summary.full_solve_percent(),
             py::arg("max_residual") = summary.max_residual, py::arg("seconds") = summary.seconds);
  if (dither != "none") d["labels"] = labels;
  return namespace_of(d);
}

std::string repr(const VModel& m) {
  std::string s = "<trivar.VModel " + std::to_string(m.num_cells()) + " cell" + (m.num_cells() == 1 ? "" : "s");
  if (m.is_glued())
    s += ", " + std::to_string(m.topology().surfaces.size()) + " V-surfaces (" +
         std::to_string(m.topology().num_boundary_surfaces()) + " boundary)";
  if (!m.materials().empty()) s += ", " + std::to_string(m.materials().size()) + " materials";
  return s + ">";
}

}  // namespace

VModel trimmed_model(std::shared_ptr<const TrimmedSolid> solid) {
  // The cell's trivariate is the identity x(u) = u on the solid's box grown by 1e-3 of its diagonal (the
  // form VCell requires of a trimmed cell; the margin keeps the boundary off the box's faces).
  Box<3> b = solid->bounding_box();
  const double grow = 1e-3 * b.diagonal();
  std::array<KnotVector, 3> knots;
  for (int d = 0; d < 3; ++d) {
    b.lo[d] -= grow;
    b.hi[d] += grow;
    knots[d] = KnotVector::open_uniform(1, 1, b.lo[d], b.hi[d]);
  }
  std::vector<double> pts;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i)
        pts.insert(pts.end(), {i ? b.hi[0] : b.lo[0], j ? b.hi[1] : b.lo[1], k ? b.hi[2] : b.lo[2]});
  VModel m;
  m.add_cell(VCell(SplineVolume::from_cartesian(knots, 3, pts), std::move(solid)));
  m.glue();
  return m;
}

void bind_vmodel(py::module_& m) {
  py::class_<VModel>(m, "VModel", "A V-model: volumetric cells (trivariates) with attributes, glued into a topology.")
      .def(py::init([](const std::vector<SplineVolume>& cells, bool glue) {
             VModel v;
             for (const SplineVolume& c : cells) v.add_cell(VCell(c));
             if (glue) v.glue();
             return v;
           }),
           py::arg("cells") = std::vector<SplineVolume>{}, py::arg("glue") = true,
           "From volumes of control dimension 3, glued (shared faces found) unless glue=False.")
      .def(
          "add_cell", [](VModel& v, const SplineVolume& c) { return v.add_cell(VCell(c)); }, py::arg("volume"),
          "Adds a cell (call glue() afterwards); returns its index.")
      .def(
          "glue", [](VModel& v, double relative_tolerance) { v.glue({.relative_tolerance = relative_tolerance}); },
          py::arg("relative_tolerance") = 1e-7, "Builds the topology (shared V-surfaces, V-curves, V-points).")
      .def_property_readonly("glued", &VModel::is_glued, "True when the topology is built.")
      .def_property_readonly("num_cells", &VModel::num_cells, "Number of cells.")
      .def("__len__", &VModel::num_cells)
      .def_property_readonly(
          "cells",
          [](const VModel& v) {
            std::vector<SplineVolume> c;
            for (const VCell& cell : v.cells()) c.push_back(cell.geometry());
            return c;
          },
          "The cells' trivariates (copies).")
      .def_property_readonly(
          "trimmed", [](const VModel& v) { return has_trimmed_cells(v); }, "True when a cell is trimmed by a B-rep.")
      .def_property_readonly(
          "num_boundary_surfaces", [](const VModel& v) { return v.topology().num_boundary_surfaces(); },
          "V-surfaces on the boundary.")
      .def_property_readonly(
          "num_shared_surfaces", [](const VModel& v) { return v.topology().num_shared_surfaces(); },
          "V-surfaces shared by two cells.")
      .def_property_readonly(
          "num_curves", [](const VModel& v) { return v.topology().curves.size(); }, "V-curves (cell edges merged).")
      .def_property_readonly(
          "num_points", [](const VModel& v) { return v.topology().points.size(); }, "V-points (cell corners merged).")
      .def(
          "neighbours", [](const VModel& v, int cell) { return v.neighbours(cell); }, py::arg("cell"),
          "Cells sharing a V-surface with `cell`.")
      .def_property_readonly(
          "bounding_box", [](const VModel& v) { return box_array<3>(v.bounding_box()); },
          "(3, 2) box of the control points.")
      .def(
          "volume",
          [](const VModel& v, int n) {
            py::gil_scoped_release release;
            return v.volume(n);
          },
          py::arg("n") = 0, "Volume (Gauss quadrature, exact for polynomial cells with n = 0).")
      .def(
          "mass",
          [](const VModel& v, const std::string& density, int n) {
            py::gil_scoped_release release;
            return v.mass(density, n);
          },
          py::arg("density"), py::arg("n") = 0, "Integral of the scalar attribute `density` over the model.")
      .def("set_attribute", &set_attribute, py::arg("name"), py::arg("value") = py::none(),
           py::arg("expression") = py::none(), py::arg("field") = py::none(), py::arg("space") = "model",
           py::arg("cells") = py::none(),
           "Sets a constant (list of values), expression (one formula per component in x, y, z, or u, v, w\n"
           "with space='parametric') or field (a Volume over [0, 1]^3) attribute on the given cells (all).")
      .def(
          "attribute_names",
          [](const VModel& v, int cell) {
            std::vector<std::string> names;
            for (const auto& [name, a] : v.cell(cell).attributes()) names.push_back(name);
            return names;
          },
          py::arg("cell") = 0)
      .def("attribute", &attribute_values, py::arg("cell"), py::arg("name"), py::arg("u"),
           "Attribute values (N, components) at cell parameters (N, 3).")
      .def_property(
          "materials",
          [](const VModel& v) {
            std::vector<std::string> names;
            for (const Material& mat : v.materials().materials()) names.push_back(mat.name);
            return names;
          },
          [](VModel& v, const std::vector<std::string>& names) {
            std::vector<Material> mats;
            for (std::size_t i = 0; i < names.size(); ++i) {
              // Display colours (palettes of PNG slices): grey levels from light to dark.
              const auto c = static_cast<std::uint8_t>(230 - (200 * i) / std::max<std::size_t>(1, names.size()));
              mats.push_back({names[i], Rgba{c, c, c, 255}});
            }
            v.set_materials(MaterialTable(std::move(mats)));
          },
          "Names of the materials the 'material' attribute's fractions refer to.")
      .def("tessellate", &tessellate, py::arg("tolerance") = 0.01,
           "Watertight boundary mesh within the chordal tolerance (as `trivar export`): vertices (V, 3),\n"
           "triangles (T, 3), per vertex its cell and cell parameters, watertight, area, volume.")
      .def("slice", &slice, py::arg("layer_thickness") = 0.027, py::arg("dpi") = std::vector<double>{600.0, 600.0},
           py::arg("z_range") = py::none(), py::arg("material") = py::none(), py::arg("dither") = "error-diffusion",
           py::arg("threads") = 0,
           "Slices into printer layers (as `trivar slice`): z (L,), cell (L, H, W) (-1 outside), fractions\n"
           "(L, H, W, materials), labels (L, H, W) after dithering (0 empty, k + 1 material k), pixel_size,\n"
           "origin and statistics. Pixel (i, j) of layer k has its centre at origin + ((i + 0.5) dx, (j + 0.5) dy),\n"
           "z[k]; row 0 is the lowest y.")
      .def("__repr__", &repr);

  m.def(
      "box",
      [](const Eigen::Vector3d& size, const Eigen::Vector3d& origin) {
        return glued(make_box({size, origin}));
      },
      py::arg("size") = Eigen::Vector3d::Ones(), py::arg("origin") = Eigen::Vector3d::Zero(),
      "A one-cell V-model of the box [origin, origin + size].");
  m.def(
      "ball",
      [](double radius, const Eigen::Vector3d& center, double core) {
        return glued(make_ball({radius, center, core}));
      },
      py::arg("radius") = 1.0, py::arg("center") = Eigen::Vector3d::Zero(), py::arg("core") = kDefaultCore,
      "Ball of 7 non-singular cells with an exact spherical boundary (as `trivar make ball`).");
  m.def(
      "cylinder",
      [](double radius, double height, double core) {
        return glued(make_cylinder({radius, height, core}));
      },
      py::arg("radius") = 1.0, py::arg("height") = 1.0, py::arg("core") = kDefaultCore,
      "Solid cylinder about the z-axis, 5 cells, exact lateral surface.");
  m.def(
      "cone",
      [](double bottom_radius, double top_radius, double height, double core) {
        return glued(make_cone({bottom_radius, top_radius, height, core}));
      },
      py::arg("bottom_radius") = 1.0, py::arg("top_radius") = 0.5, py::arg("height") = 1.0,
      py::arg("core") = kDefaultCore, "Frustum about the z-axis, 5 cells.");
  m.def(
      "torus",
      [](double major_radius, double minor_radius, double core) {
        return glued(make_torus({major_radius, minor_radius, core}));
      },
      py::arg("major_radius") = 2.0, py::arg("minor_radius") = 0.5, py::arg("core") = kDefaultCore,
      "Ring torus about the z-axis, 5 cells of revolution.");
}

}  // namespace trivar::python
