// Spline constructors: blocks, circle arcs, revolution, extrusion, ruled volumes, lofts, Coons volumes and
// sweeps (the library's model/ constructors, as `trivar make` uses them).
#include <numbers>

#include <pybind11/eigen.h>

#include "bindings.hpp"
#include "trivar/model/block.hpp"
#include "trivar/model/circle_arc.hpp"
#include "trivar/model/coons.hpp"
#include "trivar/model/extrude.hpp"
#include "trivar/model/loft.hpp"
#include "trivar/model/metamorphosis.hpp"
#include "trivar/model/revolve.hpp"
#include "trivar/model/ruled.hpp"
#include "trivar/model/sweep.hpp"

namespace trivar::python {

namespace {

template <int D>
TensorSpline<D> block(const py::object& degrees, const py::object& elements, const std::vector<double>& size) {
  require(size.size() == D, "block: size needs " + std::to_string(D) + " values, got " + std::to_string(size.size()));
  Param<D> s;
  std::copy_n(size.begin(), D, s.begin());
  return make_block<D>(ints_of<D>(degrees, "degrees"), ints_of<D>(elements, "elements"), s);
}

double radians(double degrees) { return degrees * std::numbers::pi / 180.0; }

// Volumes from surfaces and surfaces from curves share one Python name; the argument types choose.
template <int D>
void bind_lower(py::module_& m) {
  m.def(
      "revolve",
      [](const TensorSpline<D - 1>& profile, const Eigen::Vector3d& axis_point, const Eigen::Vector3d& axis,
         double angle) { return revolve<D>(profile, axis_point, axis, radians(angle)); },
      py::arg("profile"), py::arg("axis_point") = Eigen::Vector3d::Zero(), py::arg("axis") = Eigen::Vector3d(0, 0, 1),
      py::arg("angle") = 360.0,
      "Exact rational revolution of a curve (-> Surface) or surface (-> Volume) about an axis by `angle`\n"
      "degrees (as `trivar make revolve`); the angular direction is the last one.");
  m.def(
      "extrude", [](const TensorSpline<D - 1>& base, const Eigen::VectorXd& d) { return extrude<D>(base, d); },
      py::arg("base"), py::arg("direction"), "base(u) + t direction, t in [0, 1] (the new last direction).");
  m.def("extrude_along", &extrude_along<D>, py::arg("base"), py::arg("path"),
        "base translated along a path curve without turning.");
  m.def("ruled", &ruled<D>, py::arg("a"), py::arg("b"), "(1 - t) a + t b after making a and b compatible.");
  m.def("loft", py::overload_cast<const std::vector<TensorSpline<D - 1>>&, int>(&loft<D>), py::arg("sections"),
        py::arg("degree") = 3, "Interpolating loft through the sections at chord-length parameters.");
}

}  // namespace

void bind_constructors(py::module_& m) {
  m.def("block_curve", &block<1>, py::arg("degrees") = 1, py::arg("elements") = 1,
        py::arg("size") = std::vector<double>{1.0}, "The segment [0, size] on the x-axis as a curve.");
  m.def("block_surface", &block<2>, py::arg("degrees") = 1, py::arg("elements") = 1,
        py::arg("size") = std::vector<double>{1.0, 1.0}, "The rectangle [0, size] in z = 0 as a surface.");
  m.def("block", &block<3>, py::arg("degrees") = 1, py::arg("elements") = 1,
        py::arg("size") = std::vector<double>{1.0, 1.0, 1.0},
        "The box [0, size_0] x [0, size_1] x [0, size_2] with x = size * u exactly (as `trivar make box`).");
  m.def(
      "circle_arc",
      [](double radius, const Eigen::Vector3d& center, double start, double end, const Eigen::Vector3d& x_axis,
         const Eigen::Vector3d& y_axis) {
        return circle_arc(center, x_axis, y_axis, radius, radians(start), radians(end));
      },
      py::arg("radius") = 1.0, py::arg("center") = Eigen::Vector3d::Zero(), py::arg("start") = 0.0,
      py::arg("end") = 360.0, py::arg("x_axis") = Eigen::Vector3d(1, 0, 0),
      py::arg("y_axis") = Eigen::Vector3d(0, 1, 0),
      "Exact rational circle arc (degree 2, one segment per started quarter turn); angles in degrees.");
  bind_lower<2>(m);
  bind_lower<3>(m);
  m.def(
      "coons",
      [](const std::vector<SplineSurface>& faces, double tolerance) {
        require(faces.size() == 6,
                "coons: expected 6 faces (u=0, u=1, v=0, v=1, w=0, w=1), got " + std::to_string(faces.size()));
        return coons_volume({faces[0], faces[1], faces[2], faces[3], faces[4], faces[5]}, tolerance);
      },
      py::arg("faces"), py::arg("tolerance") = 1e-9, "Trilinear Coons volume (Boolean sum) of six boundary surfaces.");
  m.def("morph", &metamorphosis, py::arg("s0"), py::arg("s1"), py::arg("smoothness") = 0,
        "Metamorphosis: the volume S0 + b(w) (S1 - S0) with the smoothstep blend b of order `smoothness` (0:\n"
        "linear, as ruled; 1: 3w^2 - 2w^3), as `trivar make morph`.");
  m.def(
      "sweep",
      [](const SplineSurface& profile, const SplineCurve& path, int degree, int sections) {
        const SweepResult r = sweep(profile, path, {.degree = degree, .sections = sections});
        return py::make_tuple(r.volume, r.max_error);
      },
      py::arg("profile"), py::arg("path"), py::arg("degree") = 3, py::arg("sections") = 8,
      "Sweep of a surface along a curve with a rotation-minimising frame: (Volume, bound of the fit error).");
}

}  // namespace trivar::python
