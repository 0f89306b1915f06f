// The Python module `trivar`: the library's splines, LR splines, V-models, files, slicing and analysis with
// NumPy arrays. trivar::Error becomes trivar.Error (a ValueError) carrying the library's one-line message.
#include "bindings.hpp"
#include "trivar/spline/simd_level.hpp"

PYBIND11_MODULE(trivar, m) {
  namespace py = pybind11;
  using namespace trivar::python;
  m.doc() =
      "trivar: volumetric (trivariate) and locally refined splines for CAD, isogeometric analysis and additive\n"
      "manufacturing. Parameters and points are NumPy arrays of shape (N, d); results are NumPy arrays.";
  m.attr("__version__") = TRIVAR_VERSION;
  py::register_exception<trivar::Error>(m, "Error", PyExc_ValueError).attr("__doc__") =
      "Bad input to trivar (a file, a parameter, a knot vector): the library's one-line message naming what and where.";
  m.def(
      "simd_level", [] { return std::string(trivar::simd_level_name(trivar::simd_level())); },
      "The instruction set of the evaluation kernels chosen for this CPU.");
  bind_knot_vector(m);
  bind_tensor_splines(m);
  bind_constructors(m);
  bind_lr_splines(m);
  bind_vmodel(m);
  bind_files(m);
  bind_solve(m);
  bind_solve_model(m);
  bind_tspline(m);
  bind_hierarchical(m);
  bind_boolean(m);
  bind_fit(m);
  bind_solve_refined(m);
}
