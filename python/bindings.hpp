#pragma once
// Shared helpers of the Python module: NumPy arrays as spans of parameters (no copy when the array is a
// C-contiguous float64 array already), results allocated as NumPy arrays the library writes into, and the
// registration functions of the binding files (one per part of the library).
#include <array>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "trivar/core/box.hpp"
#include "trivar/core/error.hpp"
#include "trivar/model/model_tessellation.hpp"
#include "trivar/model/trimmed_solid.hpp"
#include "trivar/model/vmodel.hpp"

namespace trivar {
struct ModesResult;
}
namespace trivar::io::step {
struct StepTSpline;
}

namespace trivar::python {

namespace py = pybind11;

// float64, C order; pybind11 converts (copies) only what is not already so.
using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

// N points of D parameters from an (N, D) array, or one point from a (D,) array (`single` set); D = 1 also
// accepts (N,). The span aliases the array's memory: std::array<double, D> has the layout of D doubles.
template <int D>
std::span<const Param<D>> params_of(const Array& a, bool& single) {
  static_assert(sizeof(Param<D>) == D * sizeof(double));
  single = false;
  std::size_t n = 0;
  if (a.ndim() == 2 && a.shape(1) == D) {
    n = static_cast<std::size_t>(a.shape(0));
  } else if (a.ndim() == 1 && D == 1) {
    n = static_cast<std::size_t>(a.shape(0));
  } else if (a.ndim() == 1 && a.shape(0) == D) {
    n = 1;
    single = true;
  } else {
    std::string shape;
    for (py::ssize_t k = 0; k < a.ndim(); ++k) shape += (k ? ", " : "") + std::to_string(a.shape(k));
    throw Error("parameters: expected an array of shape (N, " + std::to_string(D) + ") or (" + std::to_string(D) +
                ",), got (" + shape + ")");
  }
  return {reinterpret_cast<const Param<D>*>(a.data()), n};
}

// A new float64 array of the given shape and the span the library fills.
inline py::array_t<double> new_array(const std::vector<py::ssize_t>& shape) { return py::array_t<double>(shape); }

template <class T>
std::span<T> span_of(py::array_t<T>& a) {
  return {a.mutable_data(), static_cast<std::size_t>(a.size())};
}

// Values (N, dim) at an (N, D) parameter array, or (dim,) at one (D,) point, written by `batch(params, out)` (a
// spline's batch evaluation) with the GIL released.
template <int D, class Batch>
py::array evaluate_batch(const Array& u, int dim, const Batch& batch) {
  bool single = false;
  const auto params = params_of<D>(u, single);
  auto out = new_array({static_cast<py::ssize_t>(params.size()), dim});
  {
    py::gil_scoped_release release;
    batch(params, span_of(out));
  }
  if (single) return out.attr("reshape")(dim);
  return out;
}

// The (D, 2) array of a box's bounds.
template <int D>
py::array_t<double> box_array(const Box<D>& b) {
  py::array_t<double> a({py::ssize_t{D}, py::ssize_t{2}});
  auto m = a.mutable_unchecked<2>();
  for (int k = 0; k < D; ++k) {
    m(k, 0) = b.lo[k];
    m(k, 1) = b.hi[k];
  }
  return a;
}

// Per direction k, a given int or a sequence of D ints.
template <int D>
Ints<D> ints_of(const py::object& o, const char* what) {
  Ints<D> r{};
  if (py::isinstance<py::int_>(o)) {
    r.fill(o.cast<int>());
    return r;
  }
  const auto v = o.cast<std::vector<int>>();
  require(v.size() == D,
          std::string(what) + ": expected one int or " + std::to_string(D) + " ints, got " + std::to_string(v.size()));
  for (int k = 0; k < D; ++k) r[k] = v[static_cast<std::size_t>(k)];
  return r;
}

// The boundary mesh as `trivar export` makes it: a trimmed model's stored mesh, else the adaptive tessellation
// within the chordal tolerance.
ModelTessellation boundary_mesh(const VModel& m, double tolerance);
// A one-cell V-model trimmed by a B-rep solid (as `trivar make vmodel`).
VModel trimmed_model(std::shared_ptr<const TrimmedSolid> solid);

// Eigenvalues and modes as `solve_modes` returns them: values, exact (None when empty), dofs, vectors, timings.
py::object modes_result(const ModesResult& r, const std::vector<double>& exact);

void bind_solve_model(py::module_& m);
void bind_solve_refined(py::module_& m);
void bind_knot_vector(py::module_& m);
void bind_tensor_splines(py::module_& m);
void bind_constructors(py::module_& m);
void bind_lr_splines(py::module_& m);
void bind_vmodel(py::module_& m);
void bind_files(py::module_& m);
void bind_solve(py::module_& m);
void bind_tspline(py::module_& m);
void bind_hierarchical(py::module_& m);
void bind_boolean(py::module_& m);
void bind_fit(py::module_& m);

// T-splines for read/write (tspline.cpp): a .tsm file; a T-spline JSON file (kind "t_spline"); the
// T-splines of a STEP file; whether an object is a TSplineSurface, and writing one by extension.
py::object read_tsm_file(const std::string& path, int threads = 0);
py::object read_t_spline_json_file(const std::string& path);
void append_step_t_splines(py::list& out, std::vector<io::step::StepTSpline>& splines);
bool is_t_spline(const py::handle& o);
void write_t_spline_file(const std::string& path, const py::handle& o, const std::string& step_form);

}  // namespace trivar::python
