#pragma once
// One face of a Catmull-Clark control mesh whose own corners defeat the evaluation with one extraordinary corner
// per face: several star corners (coarse cages such as a cube of one face per side, or the valence-3 and 5
// vertices everywhere in a subdivision modeller's cage) or star points joined by an edge. One uniform
// Catmull-Clark step of its neighbourhood splits the face into four sub-faces whose corners are the vertex point
// of one of the face's corners, two edge points and the face point; edge and face points of a quadrilateral
// mesh have valence 4, so each sub-face has at most one extraordinary corner and its 2N + 8 points are regular
// around it. Each quarter of the face is then a uniform bicubic B-spline patch (valence 4) or Stam's patch
// (catmull_clark_patch) of the subdivided points: still exactly the limit surface, C2 away from star points and
// G1 at them like the faces evaluated without the step. The step needs the face's two face rings (the vertex
// points of its first ring's corners take the faces around them) to be quadrilaterals, closed around every vertex,
// with one control point per vertex; the rules act on the homogeneous points (w x, w) (rational Catmull-Clark).
//
// Quarter q (0..3) is the sub-face at the face's corner q, counter-clockwise from the first corner. Its patch
// frame (s, t) in [0, 1]^2 starts at that corner along the face's side towards corner q + 1:
// (u, v) = origin + (s a + t b) / 2 with corner_frame(q)'s origin and axes, so d/du = 2 (a_u d/ds + b_u d/dt).
#include <array>
#include <vector>

#include "trivar/tspline/t_mesh.hpp"

namespace trivar {

class SubdividedFace {
public:
  // Throws trivar::Error (one line, naming the vertex or face of `mesh`) when the neighbourhood is not as above.
  SubdividedFace(const TMesh& mesh, int face);
  // The valence of the quarter's corner at the face's corner (4: a regular bicubic quarter).
  int valence(int quarter) const { return quarters_[static_cast<std::size_t>(quarter)].valence; }
  bool rational() const { return rational_; }
  // The quarter's control points in the catmull_clark_patch layout (homogeneous (w x, w y, w z, w)).
  const std::vector<std::array<double, 4>>& points(int quarter) const { return quarters_[static_cast<std::size_t>(quarter)].points; }
  // Homogeneous value, d/ds, d/dt (12 values) at (s, t) of the quarter's patch frame (at a star corner the
  // derivatives are the limit tangent directions, as in catmull_clark_patch).
  void eval_quarter(int quarter, double s, double t, double* out) const;
  // Homogeneous value, d/du, d/dv (12 values) at (u, v) in [0, 1]^2 of the face.
  void eval(double u, double v, double* out) const;

private:
  struct Quarter {
    int valence = 4;
    std::vector<std::array<double, 4>> points;
    std::vector<std::array<double, 3>> wx, w;  // split for the linear evaluation: (w x, w y, w z) and (w, 0, 0)
  };
  std::array<Quarter, 4> quarters_;
  bool rational_ = false;
};

}  // namespace trivar
