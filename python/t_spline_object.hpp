#pragma once
// The object behind trivar.TSplineSurface, shared by the T-spline bindings and the analysis on T-splines.
#include <memory>
#include <optional>
#include <string>

#include "trivar/core/error.hpp"
#include "trivar/io/tsm_format.hpp"
#include "trivar/tspline/t_mesh_surface.hpp"
#include "trivar/tspline/t_spline_surface.hpp"

namespace trivar::python {

// A T-spline as read: its three layers when the file has them, and its evaluator (or, with star points, the
// per-face evaluator of its mesh).
struct PyTSpline {
  std::string format;
  std::optional<TSpline> layers;
  std::optional<io::TsmReport> tsm;
  std::string part42_type;  // locally_refined_spline_type when read from the Part 42 form
  std::shared_ptr<const TSplineSurface> surface;
  std::shared_ptr<const TMeshSurface> mesh;

  const TSplineSurface& spline(const char* what) const {
    require(surface != nullptr, std::string(what) +
                                    ": this T-spline has star points and no global (s, t); use evaluate_face");
    return *surface;
  }
};

}  // namespace trivar::python
