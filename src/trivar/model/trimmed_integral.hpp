#pragma once
// Integrals over the region enclosed by a trimmed boundary, computed on the exact faces only (no volume
// mesh): by the divergence theorem with the field (F, 0, 0), where F(x, y, z) is an antiderivative of the
// integrand in x, the volume integral becomes the sum over faces of the integral of F n_x over the trimmed
// parameter domain, and Green's theorem turns each of those into an integral along the face's trimming loops
// of G(u, v) = int_{u0}^{u} F(S) (S_u x S_v)_x du' dv (or its counterpart along v, whichever direction of the
// face needs fewer flux points: knot spans times the inner rule's points), started per loop at the loop's own
// least coordinate. G is evaluated by LineFlux (line_flux.hpp). The loop integrals are
// Gauss-Legendre quadratures over each trimming curve's knot spans cut where it crosses the surface's knot
// lines: adaptive (a piece is accepted when a rule of half the points agrees, else halved), or, for the volume
// on polynomial faces and curves, one rule exact for the integrand's degree; G is a Gauss-Legendre sum over the
// surface's knot spans, with the fewest points exact for the volume's flux where the face is polynomial along
// that direction. Exact polynomial integrands on polynomial faces are integrated to rounding; rational faces
// (conics, spheres, tori) converge spectrally. A loop whose curves meet only within a tolerance (a kernel's vertices) is
// closed across each gap by a straight segment in the face's parameters, so a gap costs its square, not G times
// its length.
#include <array>
#include <functional>

#include "trivar/model/trimmed_boundary.hpp"

namespace trivar {

struct TrimmedIntegralOptions {
  // Relative accuracy the adaptive loop quadrature aims at (per trimming-curve span, against the face's scale).
  double relative_tolerance = 1e-12;
  // Gauss-Legendre points per span of the inner (surface) and outer (loop) quadratures.
  int points = 16;
};

// Volume enclosed by the faces (positive for outward orientation); the faces on all threads, the same result
// for any thread count.
double trimmed_volume(const TrimmedBoundary& b, const TrimmedIntegralOptions& opts = {});

// The area vector of the faces: the integral of the outward normal over them, sum over faces of S_u x S_v
// (S_v x S_u when reversed) over the trimmed domain, by the volume's quadrature with all three components in
// one pass (exact on polynomial faces and curves). Zero for a closed boundary (the divergence theorem for a
// constant field); else the volume, which trimmed_volume() takes by the divergence theorem with the field
// (x - x0, 0, 0), changes by -d times its x component when x0 moves by d.
std::array<double, 3> trimmed_area_vector(const TrimmedBoundary& b, const TrimmedIntegralOptions& opts = {});

// Integral of a density over the enclosed region. `antiderivative(x)` returns int_{x0}^{x[0]} rho(s, x[1],
// x[2]) ds for a fixed x0 (any value left of the region); it is called from one thread.
double trimmed_integral(const TrimmedBoundary& b, const std::function<double(const std::array<double, 3>&)>& antiderivative,
                        const TrimmedIntegralOptions& opts = {});

}  // namespace trivar
