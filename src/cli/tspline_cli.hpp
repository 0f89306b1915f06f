#pragma once
// The T-spline side of `trivar info|eval|convert`: Rhino .tsm files, STEP files holding T-splines (the
// seed-002 T_SPLINE_SURFACE entities or a Part 42 locally refined surface of T-spline type) and trivar's
// T-spline JSON; `trivar solve poisson` on a planar T-spline.
#include <string>
#include <vector>

namespace trivar::cli {

// True for .tsm, for a STEP file whose text names T_SPLINE_SURFACE or a T-spline locally_refined_spline_type,
// and for JSON of kind "t_spline".
bool is_t_spline_file(const std::string& path);
void print_tspline_info(const std::string& path, bool json);
// Value (order 0) or value and first derivatives (order 1) at (s, t).
void eval_tspline(const std::string& path, const std::vector<double>& params, int order);

struct TSplineConvertOptions {
  std::string step_form = "t-spline";  // STEP output: t-spline (seed-002 entities) or part42
  double tolerance = 0;                // tessellations: chordal tolerance; 0: 1e-3 of the bounding box diagonal;
                                       // patches of a model with star points: largest deviation at the star
                                       // points; 0: 1e-6 of the diagonal
  bool triangles = false;              // .vtu: the tessellation instead of exact Bezier cells
};
// To .stp/.step, .tsm, .lr (when the T-spline is an LR spline), .g2 (the LR spline, else per-element rational
// Bezier patches), .json, .vtu, .stl, .obj. A model with star points: to .tsm, to Bezier patches (t_mesh_patches:
// .g2, .json, .xml, .stp) or to triangles.
void convert_tspline(const std::string& in, const std::string& out, const TSplineConvertOptions& options);

// Poisson -lap u = 1, u = 0 on the boundary, on a planar T-spline domain (its Bezier extraction as the analysis
// space; a model with star points: the C0 multipatch space of its face patches, t_mesh_space, with refine x
// refine elements per face): prints the space and the solve; with `vtu` non-empty writes the solution as a
// surface (x, y, u).
void solve_tspline_poisson(const std::string& path, const std::string& solver, const std::string& vtu, int threads,
                           int refine);

}  // namespace trivar::cli
