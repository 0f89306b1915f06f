// TSplineSurface: T-spline surfaces from Rhino .tsm files, trivar's T-spline JSON and STEP files (the seed-002
// T_SPLINE_SURFACE entities or a Part 42 locally refined surface of T-spline type), as `trivar info|eval|convert`
// read them: evaluation on NumPy batches, the partition-of-unity defect, the analysis-suitability
// classification, tessellation and writing. A .tsm model with star points or a closed strip of faces (a torus)
// has no global (s, t): it is evaluated per face in the face's own (u, v) and tessellated; the spline queries name
// that in their errors.
#include <cmath>
#include <memory>
#include <optional>

#include "bindings.hpp"
#include "t_spline_object.hpp"
#include "trivar/io/lr_format.hpp"
#include "trivar/io/lr_g2_format.hpp"
#include "trivar/io/spline_file.hpp"
#include "trivar/io/step/step_file.hpp"
#include "trivar/io/step/t_spline_step.hpp"
#include "trivar/io/t_spline_json.hpp"
#include "trivar/io/t_spline_vtk.hpp"
#include "trivar/tspline/classification.hpp"
#include "trivar/tspline/lr_form.hpp"
#include "trivar/tspline/t_mesh_patches.hpp"
#include "trivar/tspline/t_mesh_surface.hpp"
#include "trivar/tspline/t_mesh_tessellation.hpp"
#include "trivar/tspline/t_spline_surface.hpp"
#include "trivar/tspline/t_spline_tessellation.hpp"

namespace trivar::python {

namespace {

PyTSpline from_layers(TSpline ts, std::string format) {
  PyTSpline t;
  t.format = std::move(format);
  t.surface = std::make_shared<const TSplineSurface>(ts);
  t.layers = std::move(ts);
  return t;
}

PyTSpline from_step(io::step::StepTSpline& s) {
  if (s.layers) return from_layers(std::move(*s.layers), "STEP " + s.entity);
  PyTSpline t;
  t.format = "STEP " + s.entity;
  t.part42_type = s.type;
  t.surface = std::make_shared<const TSplineSurface>(s.degrees, std::move(s.basis));
  return t;
}

template <bool kDerivatives>
py::array evaluate(const PyTSpline& t, const Array& u, int threads) {
  const TSplineSurface& s = t.spline(kDerivatives ? "derivatives" : "evaluate");
  bool single = false;
  const auto params = params_of<2>(u, single);
  const py::ssize_t n = static_cast<py::ssize_t>(params.size());
  auto out = kDerivatives ? new_array({n, 3, 3}) : new_array({n, 3});
  {
    py::gil_scoped_release release;
    if constexpr (kDerivatives) {
      double* o = out.mutable_data();
      const double nan = std::nan("");
      for (std::size_t i = 0; i < params.size(); ++i, o += 9) {
        if (s.locate(params[i]) < 0)
          std::fill_n(o, 9, nan);
        else
          s.eval_first_derivatives(params[i], o);
      }
    } else {
      s.eval_many(params, span_of(out), threads);
    }
  }
  if (single) return kDerivatives ? out.attr("reshape")(3, 3) : out.attr("reshape")(3);
  return out;
}

// Value and first derivatives (F, 3, 3) on face `face` (the file's ids, also after global steps) of a model with
// star points at (u, v) in [0, 1]^2.
py::array evaluate_face(const PyTSpline& t, int face, const Array& uv) {
  require(t.mesh != nullptr, "evaluate_face: this T-spline has a global (s, t); use evaluate or derivatives");
  require(face >= 0 && static_cast<std::size_t>(face) < t.mesh->source_mesh().faces.size() &&
              t.mesh->method(t.mesh->refined_point(face, 0, 0).face) != FaceMethod::none,
          "evaluate_face: no face " + std::to_string(face));
  bool single = false;
  const auto params = params_of<2>(uv, single);
  for (const Param<2>& p : params)
    require(p[0] >= 0 && p[0] <= 1 && p[1] >= 0 && p[1] <= 1,
            "evaluate_face: (u, v) = (" + std::to_string(p[0]) + ", " + std::to_string(p[1]) +
                ") is outside the face's [0, 1]^2");
  auto out = new_array({static_cast<py::ssize_t>(params.size()), 3, 3});
  {
    py::gil_scoped_release release;
    for (std::size_t i = 0; i < params.size(); ++i) t.mesh->eval_source(face, params[i][0], params[i][1], out.mutable_data() + 9 * i);
  }
  if (single) return out.attr("reshape")(3, 3);
  return out;
}

py::object namespace_of(const py::dict& d) { return py::module_::import("types").attr("SimpleNamespace")(**d); }

// The largest distance of the tessellation from the surface; 0: 1e-3 of the diagonal of the control net.
double tolerance_or_default(const PyTSpline& t, double tolerance) {
  if (tolerance > 0) return tolerance;
  Box<3> b = Box<3>::empty();
  if (t.mesh) {
    for (const RationalPoint& p : t.mesh->mesh().points) b.extend(p.xyz.data());
  } else {
    for (const auto& e : t.surface->bezier_elements())
      for (std::size_t i = 0; i < e.coefs.size(); i += 4) {
        const double x[3] = {e.coefs[i] / e.coefs[i + 3], e.coefs[i + 1] / e.coefs[i + 3],
                             e.coefs[i + 2] / e.coefs[i + 3]};
        b.extend(x);
      }
  }
  return 1e-3 * b.diagonal();
}

py::object tessellate_tspline(const PyTSpline& t, double tolerance, int max_per_element, int threads) {
  TSplineTriangulation m;
  const double tol = tolerance_or_default(t, tolerance);
  {
    py::gil_scoped_release release;
    m = t.mesh ? tessellate(*t.mesh, tol, max_per_element) : tessellate(*t.surface, tol, max_per_element, threads);
  }
  const auto nv = static_cast<py::ssize_t>(m.points.size());
  const auto nt = static_cast<py::ssize_t>(m.triangles.size());
  py::array_t<double> vertices({nv, py::ssize_t{3}}, nv ? &m.points[0][0] : nullptr);
  py::array_t<int> triangles({nt, py::ssize_t{3}}, nt ? &m.triangles[0][0] : nullptr);
  py::dict d(py::arg("vertices") = vertices, py::arg("triangles") = triangles, py::arg("tolerance") = tol);
  d["params"] = m.params.size() == m.points.size() && nv
                    ? py::object(py::array_t<double>({nv, py::ssize_t{2}}, &m.params[0][0]))
                    : py::object(py::none());
  return namespace_of(d);
}

// The T-spline as an LR spline (tspline/lr_form.hpp); trivar.Error with the reason when it is none.
LRSpline<2> to_lr(const PyTSpline& t) {
  std::string why;
  auto lr = lr_form(t.spline("to_lr"), why);
  require(lr.has_value(), "to_lr: the blending functions are no LR spline (" + why + ")");
  return std::move(*lr);
}

void write_tspline(const PyTSpline& t, const std::string& path, const std::string& step_form) {
  require(step_form == "t-spline" || step_form == "part42",
          "write: step_form is t-spline or part42, not '" + step_form + "'");
  const std::string ext = io::file_extension(path);
  if (t.mesh) {
    const bool patches = ext == ".g2" || ext == ".json" || ext == ".xml" || ext == ".stp" || ext == ".step";
    require(ext == ".tsm" || patches, "write: a T-spline with star points is written as .tsm or as Bezier patches (.g2, "
                                      ".json, .xml, .stp), or tessellated, not '" + ext + "'");
    py::gil_scoped_release release;
    if (!patches) return io::write_tsm(path, t.mesh->source_mesh(), t.tsm ? *t.tsm : io::TsmReport{});
    // Exact except one corner patch per face at a star point, within 1e-6 of the size (t_mesh_patches).
    std::vector<AnySpline> out;
    for (FacePatch& f : t_mesh_patches(*t.mesh).patches) out.emplace_back(std::move(f.surface));
    if (ext == ".stp" || ext == ".step")
      io::step::write_step(path, out, {});
    else
      io::write_spline_file(path, out);
    return;
  }
  const auto need_layers = [&](const char* what) {
    require(t.layers.has_value(), std::string("write: this T-spline holds the blending functions only; ") + what +
                                      " needs the three layers");
  };
  if (io::format_of(path) == io::FileFormat::step) {
    need_layers("STEP");
    py::gil_scoped_release release;
    io::step::write_t_spline_step(path, *t.layers, step_form == "part42" ? io::step::TSplineStepForm::part42
                                                                          : io::step::TSplineStepForm::t_spline_entities);
  } else if (ext == ".tsm") {
    need_layers(".tsm");
    py::gil_scoped_release release;
    io::write_tsm(path, *t.layers);
  } else if (ext == ".json") {
    need_layers("the JSON form");
    py::gil_scoped_release release;
    io::write_t_spline_json(path, *t.layers);
  } else if (ext == ".vtu") {
    py::gil_scoped_release release;
    io::write_t_spline_vtu(path, *t.surface);
  } else if (ext == ".lr" || ext == ".g2") {
    AnyLRSpline lr(to_lr(t));
    py::gil_scoped_release release;
    if (ext == ".lr")
      io::write_lr(path, {lr});
    else
      io::write_lr_g2(path, {lr});
  } else {
    throw Error("write: a T-spline is written as .stp/.step, .tsm, .json, .vtu, .lr or .g2 (tessellate for meshes), not '" +
                ext + "'");
  }
}

py::object partition_of_unity(const PyTSpline& t) {
  const PartitionOfUnity& pu = t.spline("partition_of_unity").partition_of_unity();
  return namespace_of(py::dict(py::arg("min_sum") = pu.min_sum, py::arg("max_sum") = pu.max_sum,
                               py::arg("max_defect") = pu.max_defect, py::arg("sampled_min") = pu.sampled_min,
                               py::arg("sampled_max") = pu.sampled_max, py::arg("elements_off") = pu.elements_off));
}

py::object classification(const PyTSpline& t, bool exact) {
  require(t.layers.has_value(), "classify: the classification needs the three layers (a .tsm, JSON or T_SPLINE_SURFACE file)");
  TSplineClass c;
  {
    py::gil_scoped_release release;
    c = classify(*t.layers, *t.surface, exact);
  }
  return namespace_of(py::dict(
      py::arg("t_junctions") = c.t_junctions, py::arg("gap_t_junctions") = c.gap_junctions,
      py::arg("analysis_suitable") = c.analysis_suitable,
      py::arg("crossing_extensions") = c.crossing_extensions, py::arg("dual_compatible") = c.dual.compatible,
      py::arg("dual_incompatible_pairs") = c.dual.failing_pairs, py::arg("rectangular_domain") = c.rectangular_domain,
      py::arg("standard") = c.standard, py::arg("semi_standard") = c.semi_standard,
      py::arg("linear_independence") = std::string(to_string(c.independence)),
      py::arg("part42_type") = c.part42_type()));
}

}  // namespace

py::object read_tsm_file(const std::string& path, int threads) {
  io::TsmModel m;
  PyTSpline t;
  {
    py::gil_scoped_release release;
    m = io::read_tsm(path);
    if (m.spline.image.faces.empty()) {  // star points, a closed strip of faces or sharp creases: no global (s, t)
      try {
        t.mesh = std::make_shared<const TMeshSurface>(m.mesh, threads);
      } catch (const Error& e) {
        throw Error(path + ": " + e.what());
      }
    } else {
      t = from_layers(std::move(m.spline), "TSM #TS0200");
    }
  }
  t.format = "TSM #TS0200";
  t.tsm = std::move(m.report);
  return py::cast(std::move(t));
}

py::object read_t_spline_json_file(const std::string& path) {
  PyTSpline t;
  {
    py::gil_scoped_release release;
    t = from_layers(io::read_t_spline_json(path), "trivar T-spline JSON");
  }
  return py::cast(std::move(t));
}

void append_step_t_splines(py::list& out, std::vector<io::step::StepTSpline>& splines) {
  for (io::step::StepTSpline& s : splines) out.append(py::cast(from_step(s)));
}

namespace {

// What `trivar info` prints: the layers' sizes, the .tsm report (units, deleted slots, repeated-knot nodes,
// skipped records) and, with star points, the faces by evaluation method.
py::dict info(const PyTSpline& t) {
  py::dict d(py::arg("format") = t.format);
  if (!t.part42_type.empty()) d["part42_type"] = t.part42_type;
  if (t.layers) {
    const TSpline& ts = *t.layers;
    d["t_image"] = py::dict(py::arg("vertices") = ts.image.vertices.size(), py::arg("edges") = ts.image.edges.size(),
                            py::arg("links") = ts.image.links.size(), py::arg("faces") = ts.image.faces.size(),
                            py::arg("edge_conditions") = ts.image.conditions.size());
    d["t_connect_nodes"] = ts.connect.nodes.size();
    d["t_pointset_points"] = ts.pointset.points.size();
  }
  if (t.tsm) {
    const io::TsmReport& r = *t.tsm;
    d["units"] = r.units;
    d["tolerance"] = r.tolerance;
    d["version"] = r.version;
    d["deleted_slots"] = r.deleted;
    d["deleted_faces"] = r.holes;
    d["t_junctions"] = r.t_junctions;
    d["star_points"] = r.star_points;
    d["crease_edges"] = r.crease_edges;
    d["repeated_knot_nodes"] = r.repeated_knot_nodes;
    d["skipped_records"] = r.skipped_records;
    if (!r.end_conditions.empty()) {  // Fusion 360's settings
      d["end_conditions"] = r.end_conditions;
      d["star_knot_rule"] = r.star_knot_rule;
      d["behavior_version"] = r.behavior_version;
      d["compat_version"] = r.compat_version;
    }
  }
  if (t.mesh) {
    d["faces_exact"] = t.mesh->count(FaceMethod::exact);
    d["faces_catmull_clark"] = t.mesh->count(FaceMethod::bicubic) + t.mesh->count(FaceMethod::star) + t.mesh->count(FaceMethod::subdivided);
    d["faces_at_star_points"] = t.mesh->count(FaceMethod::star);
    d["faces_subdivided"] = t.mesh->count(FaceMethod::subdivided);
    d["faces_non_uniform"] = t.mesh->count(FaceMethod::non_uniform);
    d["faces_crease"] = t.mesh->count(FaceMethod::crease);
    d["faces_averaging"] = t.mesh->count(FaceMethod::averaging);
    // The counts above are of the faces evaluated: pieces of the faces as given once T-junction lines near star
    // points are completed, each 4^global_steps faces after the global steps.
    d["global_steps"] = t.mesh->global_steps();
    d["t_junction_lines"] = t.mesh->completed_lines() ? t.mesh->completed_lines()->lines : 0;
  }
  return d;
}

}  // namespace

bool is_t_spline(const py::handle& o) { return py::isinstance<PyTSpline>(o); }

void write_t_spline_file(const std::string& path, const py::handle& o, const std::string& step_form) {
  write_tspline(o.cast<const PyTSpline&>(), path, step_form);
}

void bind_tspline(py::module_& m) {
  py::class_<PyTSpline>(m, "TSplineSurface",
                        "A T-spline surface (Rhino .tsm, trivar JSON, STEP T_SPLINE_SURFACE or Part 42 T-spline type),\n"
                        "from trivar.read. Evaluated as sum w P B / sum w B (also when the blending functions do not\n"
                        "sum to one); NaN outside the T-faces. A .tsm model with star points or a closed strip of faces\n"
                        "(a torus) has no global (s, t): use evaluate_face and tessellate.")
      .def_readonly("format", &PyTSpline::format, "The file form it was read from.")
      .def_property_readonly(
          "star_points", [](const PyTSpline& t) { return t.tsm ? t.tsm->star_points : 0; },
          "Extraordinary vertices of the .tsm mesh (0: a global T-spline).")
      .def_property_readonly(
          "has_layers", [](const PyTSpline& t) { return t.layers.has_value(); },
          "True when the T-image, T-connect and T-pointset are known (not only the blending functions).")
      .def_property_readonly(
          "degrees",
          [](const PyTSpline& t) {
            return t.mesh ? Ints<2>{t.mesh->mesh().degree, t.mesh->mesh().degree} : t.surface->degrees();
          },
          "Degree per direction.")
      .def_property_readonly(
          "domain", [](const PyTSpline& t) { return box_array<2>(t.spline("domain").domain()); },
          "(2, 2) bounds of (s, t).")
      .def_property_readonly(
          "num_basis", [](const PyTSpline& t) { return t.spline("num_basis").basis().size(); },
          "Number of blending functions (T-nodes).")
      .def_property_readonly(
          "num_faces",
          [](const PyTSpline& t) {
            return t.mesh ? static_cast<int>(t.mesh->source_mesh().faces.size())
                          : static_cast<int>(t.layers ? t.layers->image.faces.size() : 0);
          },
          "Faces of the T-mesh as given, the ids evaluate_face takes (0 when only the blending functions are known).")
      .def_property_readonly(
          "elements",
          [](const PyTSpline& t) {
            const auto e = t.spline("elements").elements();
            auto a = new_array({static_cast<py::ssize_t>(e.size()), 2, 2});
            double* p = a.mutable_data();
            for (const Box<2>& b : e) *p++ = b.lo[0], *p++ = b.hi[0], *p++ = b.lo[1], *p++ = b.hi[1];
            return a;
          },
          "Bezier elements (E, 2, 2): the cells of the grid of all knot values inside the T-faces.")
      .def_property_readonly(
          "units", [](const PyTSpline& t) { return t.tsm ? t.tsm->units : std::string(); },
          "Units of a .tsm file, e.g. '1 millimeters' (empty otherwise).")
      .def_property_readonly("partition_of_unity", &partition_of_unity,
                             "Sum of the blending functions: min_sum, max_sum (Bezier bounds), sampled_min, sampled_max,\n"
                             "max_defect (max |Bernstein coefficient - 1|, 0 for a partition of unity), elements_off.")
      .def("info", &info,
           "What `trivar info` reports beyond the properties: format, T-image / T-connect / T-pointset sizes, the\n"
           ".tsm report (units, tolerance, version, deleted_slots, deleted_faces, t_junctions, star_points,\n"
           "crease_edges (sharp creases: ec between two faces of a SUBD_CREASES file), repeated_knot_nodes,\n"
           "skipped_records) and, with star points, the faces by evaluation method (refined faces after global_steps).")
      .def("classify", &classification, py::arg("exact") = true,
           "Analysis-suitability as `trivar info`: t_junctions, gap_t_junctions (of those, facing each other across\n"
           "gaps no ray crosses: no extension), analysis_suitable, crossing_extensions,\n"
           "dual_compatible, standard, semi_standard, linear_independence, part42_type (exact: the exact rank test\n"
           "when peeling is inconclusive).")
      .def_property_readonly(
          "analysis_suitable",
          [](const PyTSpline& t) {
            const py::object c = classification(t, false);
            return c.attr("analysis_suitable").cast<bool>();
          },
          "True when no horizontal and vertical T-junction extensions cross (Li et al. 2012).")
      .def("__call__", &evaluate<false>, py::arg("u"), py::arg("threads") = 0,
           "Points (N, 3) at parameters (N, 2) in (s, t); NaN outside the T-faces.")
      .def("evaluate", &evaluate<false>, py::arg("u"), py::arg("threads") = 0, "Same as calling the T-spline.")
      .def("derivatives", &evaluate<true>, py::arg("u"), py::arg("threads") = 0,
           "Value, d/ds, d/dt (N, 3, 3) at parameters (N, 2); NaN outside the T-faces.")
      .def("evaluate_face", &evaluate_face, py::arg("face"), py::arg("uv"),
           "A model with star points: value, d/du, d/dv (N, 3, 3) at (u, v) in [0, 1]^2 of one face.")
      .def("tessellate", &tessellate_tspline, py::arg("tolerance") = 0.0, py::arg("max_per_element") = 64,
           py::arg("threads") = 0,
           "Triangles within the chordal tolerance (0: 1e-3 of the control net's diagonal, as `trivar convert`):\n"
           "vertices (V, 3), triangles (T, 3), params (V, 2) in (s, t) (with star points: in each face's (u, v)), tolerance.")
      .def("to_lr", &to_lr, "The same surface as an LRSurface (blending functions that sum to one).")
      .def("write", &write_tspline, py::arg("path"), py::arg("step_form") = "t-spline",
           "Writes by extension: .stp/.step (step_form 't-spline': T_SPLINE_SURFACE entities, or 'part42'), .tsm,\n"
           ".json, .vtu (exact Bezier cells), .lr and .g2 (as an LR spline); meshes through tessellate and\n"
           "trivar.write_mesh.")
      .def("__repr__", [](const PyTSpline& t) {
        if (t.mesh)
          return "<trivar.TSplineSurface degree " + std::to_string(t.mesh->mesh().degree) + ", " +
                 std::to_string(t.mesh->source_mesh().faces.size()) + " faces, " + std::to_string(t.tsm->star_points) + " star points>";
        return "<trivar.TSplineSurface degrees (" + std::to_string(t.surface->degrees()[0]) + ", " +
               std::to_string(t.surface->degrees()[1]) + "), " + std::to_string(t.surface->basis().size()) +
               " blending functions, " + std::to_string(t.surface->elements().size()) + " elements>";
      });
}

}  // namespace trivar::python
