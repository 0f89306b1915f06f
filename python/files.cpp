// Files by extension: every format trivar reads or writes, for tensor splines, LR splines and V-models, and the
// B-rep solids of STEP files as trimmed V-models (OpenCASCADE, the cad layer).
#include <fstream>

#include "bindings.hpp"
#include "trivar/cad/step_import.hpp"
#include "trivar/io/amf_writer.hpp"
#include "trivar/io/gismo_xml.hpp"
#include "trivar/io/json_format.hpp"
#include "trivar/io/lr_format.hpp"
#include "trivar/io/lr_g2_format.hpp"
#include "trivar/io/lr_json.hpp"
#include "trivar/io/lr_vtk.hpp"
#include "trivar/io/spline_file.hpp"
#include "trivar/io/step/step_file.hpp"
#include "trivar/io/stl_writer.hpp"
#include "trivar/io/threemf_writer.hpp"
#include "trivar/io/vmodel_json.hpp"
#include "trivar/io/vmodel_vtk.hpp"
#include "trivar/model/closure_defect.hpp"
#include "trivar/model/model_tessellation.hpp"
#include "trivar/model/trimmed_tessellation.hpp"

namespace trivar::python {

namespace {

py::object to_python(const AnySpline& s) {
  return std::visit([](const auto& x) { return py::cast(x); }, s);
}
py::object to_python(const AnyLRSpline& s) {
  return std::visit([](const auto& x) { return py::cast(x); }, s);
}

// GoTools streams start with the first object's class number: 293 / 793 are LR splines.
bool g2_holds_lr(const std::string& path) {
  std::ifstream in(path);
  require(static_cast<bool>(in), path + ": cannot open");
  int type = 0;
  in >> type;
  return type == 293 || type == 793;
}

bool is_lr_kind(const nlohmann::json& j) {
  return j.is_object() && j.contains("kind") && (j["kind"] == "lr_surface" || j["kind"] == "lr_volume");
}

py::list read_file(const std::string& path) {
  py::list out;
  const std::string ext = io::file_extension(path);
  if (ext == ".tsm") {
    out.append(read_tsm_file(path));
    return out;
  }
  if (ext == ".xml") {
    // G+Smo: tensor and hierarchical geometries, in document order.
    std::vector<io::GismoGeometry> all;
    {
      py::gil_scoped_release release;
      all = io::read_gismo_xml(path);
    }
    for (const io::GismoGeometry& g : all) out.append(std::visit([](const auto& x) { return py::cast(x); }, g));
    return out;
  }
  if (ext == ".json") {
    {
      // T-spline JSON has its own layout (io/t_spline_json.hpp), without the "trivar" header of the others.
      std::ifstream in(path);
      const nlohmann::json peek = nlohmann::json::parse(in, nullptr, false);
      if (peek.is_object() && peek.value("kind", "") == "t_spline") {
        out.append(read_t_spline_json_file(path));
        return out;
      }
    }
    nlohmann::json doc;
    {
      py::gil_scoped_release release;
      doc = io::read_json_document(path);
    }
    if (io::is_vmodel_json(doc)) {
      out.append(io::vmodel_from_json(doc, path));
      return out;
    }
    for (const auto& [object, where] : io::object_documents(doc, path, "objects")) {
      if (is_lr_kind(object))
        out.append(to_python(io::lr_spline_from_json(object, where)));
      else
        out.append(to_python(io::spline_from_json(object, where)));
    }
    return out;
  }
  if (ext == ".lr" || (ext == ".g2" && g2_holds_lr(path))) {
    std::vector<AnyLRSpline> lr;
    {
      py::gil_scoped_release release;
      lr = ext == ".lr" ? io::read_lr(path) : io::read_lr_g2(path);
    }
    for (const AnyLRSpline& s : lr) out.append(to_python(s));
    return out;
  }
  if (io::file_format(path, true) == io::FileFormat::step) {
    io::step::StepContents c;
    {
      py::gil_scoped_release release;
      c = io::step::read_step(path);
    }
    for (const AnySpline& s : c.splines) out.append(to_python(s));
    for (const AnyLRSpline& s : c.lr_splines) out.append(to_python(s));
    append_step_t_splines(out, c.t_splines);
    return out;
  }
  std::vector<AnySpline> splines;
  {
    py::gil_scoped_release release;
    splines = io::read_spline_file(path);
  }
  for (const AnySpline& s : splines) out.append(to_python(s));
  return out;
}

void write_model(const std::string& path, const VModel& m, double tolerance) {
  const std::string ext = io::file_extension(path);
  py::gil_scoped_release release;
  if (ext == ".json") {
    io::write_vmodel(path, m);
  } else if (ext == ".vtu") {
    io::write_vmodel_vtu(path, m);
  } else if (ext == ".stl") {
    const ModelTessellation t = boundary_mesh(m, tolerance);
    require(!t.mesh.triangles.empty() && is_watertight(t.mesh),
            "write: the boundary mesh of the model is empty or not watertight; nothing written");
    io::write_stl(path, t.mesh);
  } else {
    throw Error("write: a V-model is written as .json, .vtu or .stl, not '" + ext + "'");
  }
}

void write_file(const std::string& path, const py::object& objects, double tolerance, const std::string& step_form) {
  if (py::isinstance<VModel>(objects)) return write_model(path, objects.cast<const VModel&>(), tolerance);
  if (is_t_spline(objects)) return write_t_spline_file(path, objects, step_form);
  std::vector<AnySpline> splines;
  std::vector<AnyLRSpline> lr;
  std::vector<AnyHierarchicalSpline> hier;
  const py::list list = py::isinstance<py::list>(objects) || py::isinstance<py::tuple>(objects)
                            ? py::list(objects)
                            : py::list(py::make_tuple(objects));
  for (const py::handle o : list) {
    if (py::isinstance<SplineCurve>(o))
      splines.emplace_back(o.cast<SplineCurve>());
    else if (py::isinstance<SplineSurface>(o))
      splines.emplace_back(o.cast<SplineSurface>());
    else if (py::isinstance<SplineVolume>(o))
      splines.emplace_back(o.cast<SplineVolume>());
    else if (py::isinstance<LRSpline<2>>(o))
      lr.emplace_back(o.cast<LRSpline<2>>());
    else if (py::isinstance<LRSpline<3>>(o))
      lr.emplace_back(o.cast<LRSpline<3>>());
    else if (py::isinstance<HierarchicalSpline<2>>(o))
      hier.emplace_back(o.cast<HierarchicalSpline<2>>());
    else if (py::isinstance<HierarchicalSpline<3>>(o))
      hier.emplace_back(o.cast<HierarchicalSpline<3>>());
    else
      throw Error("write: cannot write a " + std::string(py::str(o.get_type().attr("__name__"))) +
                  " (Curve, Surface, Volume, LRSurface, LRVolume, HierarchicalSurface, HierarchicalVolume, a list of\n"
                  "them, a TSplineSurface or a VModel)");
  }
  require(!splines.empty() || !lr.empty() || !hier.empty(), "write: nothing to write");
  const std::string ext = io::file_extension(path);
  py::gil_scoped_release release;
  if (io::format_of(path) == io::FileFormat::step) {
    io::step::write_step(path, splines, lr, hier);
  } else if (!hier.empty()) {
    require(lr.empty(), "write: hierarchical and LR splines together are written to STEP only (.stp, .step)");
    if (ext == ".vtu") {
      require(splines.empty(), "write: hierarchical and tensor splines together go to .xml or STEP, not .vtu");
      io::write_hierarchical_vtu(path, hier);
      return;
    }
    require(ext == ".xml", "write: hierarchical splines are written as G+Smo .xml, .vtu or .stp, not '" + ext + "'");
    std::vector<io::GismoGeometry> g;
    for (const AnySpline& s : splines) {
      if (const auto* x = std::get_if<TensorSpline<2>>(&s)) g.emplace_back(*x);
      else if (const auto* y = std::get_if<TensorSpline<3>>(&s)) g.emplace_back(*y);
      else throw Error("write: a G+Smo .xml file holds surfaces and volumes, not curves");
    }
    for (const AnyHierarchicalSpline& h : hier) std::visit([&](const auto& x) { g.emplace_back(x); }, h);
    io::write_gismo_xml(path, g);
  } else if (!lr.empty()) {
    require(splines.empty(), "write: tensor and LR splines together are written to STEP only (.stp, .step)");
    if (ext == ".lr")
      io::write_lr(path, lr);
    else if (ext == ".g2")
      io::write_lr_g2(path, lr);
    else if (ext == ".json")
      io::write_lr_json(path, lr);
    else if (ext == ".vtu")
      io::write_lr_vtu(path, lr);
    else
      throw Error("write: LR splines are written as .lr, .g2, .json, .vtu or .stp, not '" + ext + "'");
  } else {
    io::write_spline_file(path, splines);
  }
}

// A triangle mesh from arrays, by extension: .stl, or .3mf / .amf with materials and per-vertex fractions
// (3MF composite materials; AMF vertex colours, or the composite of `formulas` in x, y, z).
void write_mesh(const std::string& path, const Array& vertices,
                const py::array_t<int, py::array::c_style | py::array::forcecast>& triangles,
                const std::vector<std::string>& materials, const std::optional<Array>& fractions,
                const std::vector<std::string>& formulas) {
  require(vertices.ndim() == 2 && vertices.shape(1) == 3, "write_mesh: vertices must have shape (V, 3)");
  require(triangles.ndim() == 2 && triangles.shape(1) == 3, "write_mesh: triangles must have shape (T, 3)");
  TriangleMesh mesh;
  mesh.vertices.resize(static_cast<std::size_t>(vertices.shape(0)));
  mesh.triangles.resize(static_cast<std::size_t>(triangles.shape(0)));
  std::copy_n(vertices.data(), vertices.size(), &mesh.vertices[0][0]);
  std::copy_n(triangles.data(), triangles.size(), &mesh.triangles[0][0]);
  const std::string ext = io::file_extension(path);
  if (ext == ".stl") {
    py::gil_scoped_release release;
    io::write_stl(path, mesh);
    return;
  }
  require(ext == ".3mf" || ext == ".amf", "write_mesh: a mesh is written as .stl, .3mf or .amf, not '" + ext + "'");
  std::vector<Material> list;
  for (std::size_t i = 0; i < materials.size(); ++i) {
    // Display colours: grey levels from light to dark, as VModel.materials.
    const auto c = static_cast<std::uint8_t>(230 - (200 * i) / std::max<std::size_t>(1, materials.size()));
    list.push_back({materials[i], Rgba{c, c, c, 255}});
  }
  const MaterialTable table(std::move(list));
  std::vector<double> f;
  if (fractions) f.assign(fractions->data(), fractions->data() + fractions->size());
  py::gil_scoped_release release;
  if (ext == ".3mf")
    io::write_3mf(path, mesh, table, f);
  else
    io::write_amf(path, mesh, table, {.base_material = 0, .formulas = formulas}, f);
}

}  // namespace

ModelTessellation boundary_mesh(const VModel& m, double tolerance) {
  return has_trimmed_cells(m) ? trimmed_boundary_mesh(m) : tessellate_boundary(m, {.chordal_tolerance = tolerance});
}

void bind_files(py::module_& m) {
  m.def("read", &read_file, py::arg("path"),
        "The objects of a file by extension: .json (splines, LR splines, a T-spline or one V-model), .g2\n"
        "(GoTools, LR 293/793 too), .lr (LRsplines), .xml (G+Smo tensor and THB/HB geometries), .tsm (Rhino\n"
        "T-splines), .stp/.step/.p21 (Part 42 spline curves, surfaces, volumes, locally refined splines and\n"
        "T-splines). Returns a list.");
  m.def("write", &write_file, py::arg("path"), py::arg("objects"), py::arg("tolerance") = 0.01,
        py::arg("step_form") = "t-spline",
        "Writes by extension: splines to .json, .g2, .xml, .vtu, .stp; LR splines to .lr, .g2, .json, .vtu,\n"
        ".stp; hierarchical splines to .xml (with tensor splines), .vtu, .stp (their HB form); a TSplineSurface\n"
        "to .tsm, .json, .vtu, .lr, .g2, .stp (step_form 't-spline' or 'part42'; one with star points to .tsm or\n"
        "as Bezier patches to .g2, .json, .xml, .stp); a VModel to .json, .vtu or .stl\n"
        "(watertight boundary within `tolerance`). Nothing is written on error; existing files are replaced\n"
        "atomically.");
  m.def("write_mesh", &write_mesh, py::arg("path"), py::arg("vertices"), py::arg("triangles"),
        py::arg("materials") = std::vector<std::string>{"part"}, py::arg("fractions") = py::none(),
        py::arg("formulas") = std::vector<std::string>{},
        "Writes a triangle mesh (vertices (V, 3), triangles (T, 3), e.g. from VModel.tessellate) for printers by\n"
        "extension: .stl; .3mf with per-vertex material fractions (V, materials) as composite materials; .amf\n"
        "with vertex colours from the fractions, or a composite material of one formula in x, y, z per material.");
  m.def(
      "import_step",
      [](const std::string& path, double tolerance, bool kernel_volume) {
        cad::StepImport im;
        {
          py::gil_scoped_release release;
          im = cad::import_step(path, {.chordal_tolerance = tolerance, .kernel_volume = kernel_volume});
        }
        py::list models;
        for (const cad::ImportedSolid& s : im.solids) {
          require(s.solid != nullptr, [&] {
            return path + ": " + s.name + ": " + std::to_string(im.report.unmapped.size()) +
                   " faces could not be mapped" +
                   (im.report.unmapped.empty()
                        ? ""
                        : " (" + im.report.unmapped.front().name + ": " + im.report.unmapped.front().reason + ")");
          });
          const auto ns = py::module_::import("types").attr("SimpleNamespace");
          const ClosureDefect& c = *s.closure;
          models.append(ns(py::arg("name") = s.name, py::arg("model") = trimmed_model(s.solid),
                           py::arg("kernel_volume") = s.kernel_volume ? py::object(py::float_(*s.kernel_volume)) : py::object(py::none()),
                           py::arg("closure") = ns(py::arg("area_vector") = py::make_tuple(c.area_vector[0], c.area_vector[1], c.area_vector[2]),
                                                   py::arg("norm") = c.norm, py::arg("area") = c.area, py::arg("relative") = c.relative,
                                                   py::arg("volume_uncertainty") = c.volume_uncertainty,
                                                   py::arg("allowance") = c.allowance, py::arg("closed") = c.closed())));
        }
        return models;
      },
      py::arg("path"), py::arg("tolerance") = 0.0, py::arg("kernel_volume") = false,
      "The B-rep solids of a STEP file, each as (name, model, kernel_volume, closure): a trimmed one-cell V-model\n"
      "(as `trivar make vmodel`: exact NURBS faces with trimming loops; volume, tessellate, slice and write work\n"
      "on it), with kernel_volume=True OpenCASCADE's volume of the solid as read (else None), and how far its\n"
      "faces are from closing (area_vector: the integral of the outward normal, zero for a closed boundary; norm,\n"
      "area, relative, volume_uncertainty, allowance, closed). tolerance: chordal tolerance of the boundary mesh\n"
      "(0: 1e-3 of the part's diagonal).");
}

}  // namespace trivar::python
