// libFuzzer target for the .tsm reader (Rhino's and Fusion 360's files): any input must read or throw
// trivar::Error; every T-spline read must build (blending functions, Bezier elements), evaluate with first
// derivatives at its domain's corners and centre, classify and tessellate coarsely, throwing nothing but
// trivar::Error; a model without a global (s, t) (star points, a closed strip of faces) builds its per-face
// surface, evaluates every face's corners and centre and tessellates coarsely. A violation traps.
// Build and run: see fuzz/CMakeLists.txt (seeds: fuzz/tsm).
#include <cstddef>
#include <cstdint>
#include <string>

#include "spline_checks.hpp"
#include "trivar/core/error.hpp"
#include "trivar/io/tsm_format.hpp"
#include "trivar/tspline/classification.hpp"
#include "trivar/tspline/t_mesh_surface.hpp"
#include "trivar/tspline/t_mesh_tessellation.hpp"
#include "trivar/tspline/t_spline_surface.hpp"
#include "trivar/tspline/t_spline_tessellation.hpp"

using namespace trivar;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const io::TsmModel m = io::parse_tsm(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.tsm");
    double out[9];
    if (m.spline.image.faces.empty()) {
      const TMeshSurface s(m.mesh, 1);
      for (int f = 0; f < s.num_faces(); ++f)
        if (s.method(f) != FaceMethod::none)
          for (double u : {0.0, 0.5, 1.0}) s.eval(f, u, u, out);
      if (s.num_faces() < 256) tessellate(s, 1e-2, 2);
      return 0;
    }
    const TSplineSurface s(m.spline, 1);
    for (int corner = 0; corner <= 4; ++corner) s.eval_first_derivatives(fuzz::corner_or_centre(s.domain(), corner), out);
    classify(m.spline, s, false);
    if (s.elements().size() < 256) tessellate(s, 1e-2 * s.domain().diagonal() + 1e-9, 2, 1);
  } catch (const Error&) {
  }
  return 0;
}
