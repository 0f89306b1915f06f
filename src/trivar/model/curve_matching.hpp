#pragma once
// Which V-curve a cell edge lies on: the matching rule shared by gluing (cell edges of untrimmed cells) and
// trimmed cells (their trimming edges).
#include <array>
#include <functional>
#include <span>
#include <vector>

namespace trivar {

struct CurveMatch {
  int candidate = -1;     // index into the candidates; -1: none matches
  bool reversed = false;  // the edge runs from the V-curve's end to its start
};

// A V-curve already found, as the matcher sees it: its end V-points and its first edge's interior samples, taken
// at the same fractions of the parameter range as the edge's.
struct CurveCandidate {
  std::array<int, 2> points;
  std::span<const std::array<double, 3>> samples;
};

// The first candidate with the edge's end V-points (p0, p1), in either direction, whose samples are within `tol`
// of the edge's samples or, when the two are parametrised differently, whose curve passes within `tol` of every
// sample of the edge (`distance_to(candidate index, point)`, infinite when no curve is known). A closed edge matches
// in either direction; whether its first sample lies nearer the candidate's first or last sample decides which.
CurveMatch match_curve(std::span<const CurveCandidate> candidates, int p0, int p1,
                       std::span<const std::array<double, 3>> samples, double tol,
                       const std::function<double(std::size_t, const std::array<double, 3>&)>& distance_to);

}  // namespace trivar
