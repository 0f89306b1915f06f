// T-meshes with star points as Bezier patches: exact pieces against the surface's own evaluation, corner
// patches against the Catmull-Clark limit surface, continuity across faces, between the pieces of a face and at
// the star points, deviation against the number of levels.
#include <gtest/gtest.h>

#include <cstdio>

#include "face_continuity.hpp"
#include "star_mesh_tsm.hpp"
#include "trivar/io/tsm_format.hpp"
#include "trivar/tspline/t_mesh_patches.hpp"

namespace trivar {
namespace {

double fan_height(double x, double y) { return 0.05 * x * x - 0.03 * x * y + 0.2 * std::sin(0.4 * y); }

// The patches of each face as one surface evaluated face by face (value, d/du, d/dv in the face's (u, v)).
class Patched {
public:
  explicit Patched(const TMeshPatches& p) : p_(p) {
    for (std::size_t i = 0; i < p.patches.size(); ++i) {
      const auto f = static_cast<std::size_t>(p.patches[i].face);
      if (by_face_.size() <= f) by_face_.resize(f + 1);
      by_face_[f].push_back(static_cast<int>(i));
    }
  }
  const std::vector<int>& of(int face) const { return by_face_[static_cast<std::size_t>(face)]; }
  void eval(int face, double u, double v, double* out) const {
    for (int i : of(face)) {
      const FacePatch& q = p_.patches[static_cast<std::size_t>(i)];
      if (q.piece.contains({u, v}, 1e-15)) return q.surface.eval_derivs({u, v}, 1, out);
    }
    ADD_FAILURE() << "no patch of face " << face << " holds (" << u << ", " << v << ")";
  }

private:
  const TMeshPatches& p_;
  std::vector<std::vector<int>> by_face_;
};

double sine(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return std::hypot(a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]);
}

// Positions along an edge: the tenths and, towards both ends, the middles of the dyadic pieces down to 2^-levels.
std::vector<double> edge_samples(int levels) {
  std::vector<double> t = test::tenths();
  for (int j = 1; j <= levels + 1; ++j) {
    t.push_back(std::ldexp(0.75, -j));
    t.push_back(1 - std::ldexp(0.75, -j));
  }
  return t;
}

struct Model {
  const char* name;
  io::TsmModel model;
};

std::vector<Model> models() {
  std::vector<Model> m;
  m.push_back({"cube", io::parse_tsm(test::tsm_text(test::cube_mesh(3)), "cube.tsm")});
  m.push_back({"valence-5 fan", io::parse_tsm(test::tsm_text(test::fan_mesh(5, 8, fan_height)), "fan5.tsm")});
  m.push_back({"valence-3 fan", io::parse_tsm(test::tsm_text(test::fan_mesh(3, 8, fan_height)), "fan6.tsm")});
  return m;
}

// Exact pieces are the surface to rounding; corner patches stay within the tolerance of the limit surface
// (sampled at points other than the 9 x 9 the level choice used); the counts follow the construction.
TEST(TMeshPatches, ExactPiecesAreTheSurfaceAndCornersMeetTheTolerance) {
  for (const Model& m : models()) {
    const TMeshSurface s(m.model.mesh, 1);
    const TMeshPatches p = t_mesh_patches(s);
    EXPECT_LE(p.deviation, p.tolerance);
    EXPECT_GT(p.levels, 2);
    EXPECT_EQ(p.corner_patches, s.count(FaceMethod::star));
    // The hand-built meshes have one Bezier element per exact face.
    EXPECT_EQ(p.exact_patches, s.count(FaceMethod::exact) + s.count(FaceMethod::bicubic) + 3 * p.levels * s.count(FaceMethod::star));
    double exact = 0, corner = 0;
    for (const FacePatch& q : p.patches) {
      EXPECT_FALSE(q.surface.is_rational());
      for (double a : {0.0, 0.137, 0.5, 0.77, 1.0})
        for (double b : {0.0, 0.29, 0.61, 1.0}) {
          const double u = q.piece.lo[0] + a * q.piece.extent(0), v = q.piece.lo[1] + b * q.piece.extent(1);
          double x[9], y[3];
          s.eval(q.face, u, v, x);
          q.surface.eval({u, v}, y);
          const double d = std::hypot(x[0] - y[0], x[1] - y[1], x[2] - y[2]);
          (q.exact ? exact : corner) = std::max(q.exact ? exact : corner, d);
        }
    }
    EXPECT_LT(exact, 1e-13);
    EXPECT_LE(corner, 2 * p.tolerance);
    std::printf("%s: %zu patches (%d corner), %d levels, exact pieces off the surface by %.1e, corner patches by %.2e "
                "(tolerance %.2e)\n",
                m.name, p.patches.size(), p.corner_patches, p.levels, exact, corner, p.tolerance);
  }
}

// C0 across every face edge and between the pieces of a face (where their sides meet at T-junctions), G1 at the
// star points, and the normal jump across the edges at star points, which shrinks with the levels.
TEST(TMeshPatches, ContinuityOfThePatchedSurface) {
  for (const Model& m : models()) {
    const TMeshSurface s(m.model.mesh, 1);
    double previous_normal = 1;
    for (int levels : {0, 3, 6, 10}) {
      TMeshPatchOptions o;
      o.levels = levels;
      const TMeshPatches p = t_mesh_patches(s, o);
      const Patched ps(p);
      const test::Continuity c = test::continuity(
          s.mesh(), [&](int f, double u, double v, double* out) { ps.eval(f, u, v, out); }, edge_samples(levels));
      EXPECT_LT(c.gap, 1e-13) << m.name << ' ' << levels;
      // Inside a face: every piece's sides against the other pieces that hold the same (u, v).
      double inner_gap = 0, inner_normal = 0;
      for (int f = 0; f < s.num_faces(); ++f) {
        if (s.method(f) != FaceMethod::star) continue;
        for (int i : ps.of(f)) {
          const FacePatch& a = p.patches[static_cast<std::size_t>(i)];
          for (int side = 0; side < 4; ++side)
            for (double t : {0.0, 0.25, 0.5, 0.75, 1.0}) {
              const auto uv = test::side_uv(side, t);
              const double u = a.piece.lo[0] + uv[0] * a.piece.extent(0), v = a.piece.lo[1] + uv[1] * a.piece.extent(1);
              if (u <= 0 || u >= 1 || v <= 0 || v >= 1) continue;
              double x[9];
              a.surface.eval_derivs({u, v}, 1, x);
              for (int j : ps.of(f)) {
                const FacePatch& b = p.patches[static_cast<std::size_t>(j)];
                if (j == i || !b.piece.contains({u, v}, 1e-15)) continue;
                double y[9];
                b.surface.eval_derivs({u, v}, 1, y);
                inner_gap = std::max(inner_gap, std::hypot(x[0] - y[0], x[1] - y[1], x[2] - y[2]));
                inner_normal = std::max(inner_normal, sine(test::unit_normal(x), test::unit_normal(y)));
              }
            }
        }
      }
      EXPECT_LT(inner_gap, 1e-13) << m.name << ' ' << levels;
      // G1 at the star point: each corner patch's normal there is the limit surface's normal.
      double star_normal = 0;
      for (const FacePatch& q : p.patches) {
        if (q.exact) continue;
        const std::array<double, 2> at = corner_frame(s.patch_corner(q.face)).origin;
        double x[9], y[9];
        q.surface.eval_derivs({at[0], at[1]}, 1, x);
        s.eval(q.face, at[0], at[1], y);
        EXPECT_LT(std::hypot(x[0] - y[0], x[1] - y[1], x[2] - y[2]), 1e-14);
        star_normal = std::max(star_normal, sine(test::unit_normal(x), test::unit_normal(y)));
      }
      EXPECT_LT(star_normal, 1e-12) << m.name << ' ' << levels;
      if (levels >= 3) {
        EXPECT_LT(c.normal_angle, previous_normal) << m.name << ' ' << levels;
      }
      previous_normal = c.normal_angle;
      std::printf("%s, %2d levels: deviation %.2e; across face edges: gap %.1e, normal jump (sine) %.2e; inside faces: "
                  "gap %.1e, normal jump %.2e; at star points: normal off the limit normal %.1e\n",
                  m.name, levels, p.deviation, c.gap, c.normal_angle, inner_gap, inner_normal, star_normal);
    }
  }
}

// The corner patch's deviation from the limit surface falls with every level, about as the subdominant
// eigenvalue of the subdivision (the corner region shrinks by lambda per level).
TEST(TMeshPatches, DeviationFallsWithTheLevels) {
  for (const Model& m : models()) {
    const TMeshSurface s(m.model.mesh, 1);
    std::vector<double> dev;
    for (int levels = 0; levels <= 12; levels += 4) {
      TMeshPatchOptions o;
      o.levels = levels;
      dev.push_back(t_mesh_patches(s, o).deviation);
    }
    for (std::size_t i = 1; i < dev.size(); ++i) EXPECT_LT(dev[i], 0.5 * dev[i - 1]) << m.name << ' ' << i;
    std::printf("%s: deviation at 0, 4, 8, 12 levels: %.2e %.2e %.2e %.2e\n", m.name, dev[0], dev[1], dev[2], dev[3]);
    // A tolerance out of reach within max_levels is refused with the deviation reached.
    TMeshPatchOptions tight;
    tight.tolerance = 1e-30;
    tight.max_levels = 3;
    try {
      t_mesh_patches(s, tight);
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("after 3 levels"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace trivar
