// trivar's own P21 reader (io/step) and OpenCASCADE read the same B-spline surfaces from a STEP file: the
// surfaces must agree wherever both read them.
#include <gtest/gtest.h>

#include <BRepBuilderAPI_NurbsConvert.hxx>
#include <unistd.h>

#include <variant>

#include "cad/occt_solids.hpp"
#include "trivar/cad/step_import.hpp"
#include "trivar/io/step/step_file.hpp"

using namespace trivar;

TEST(ReaderAgreement, BsplineSurfacesAgreeWithTheP21Reader) {
  const auto dir = test::temp_dir("agree");
  // Every face a B_SPLINE_SURFACE_WITH_KNOTS (rational ones for the cylinder and the fillets' spheres).
  for (const auto& [name, shape] : {std::pair{"fused", test::fused_box_cylinder()}, {"filleted", test::filleted_block()}}) {
    SCOPED_TRACE(name);
    const std::string path = test::write_step(BRepBuilderAPI_NurbsConvert(shape, true).Shape(), dir, name);
    const io::step::StepContents c = io::step::read_step(path);
    const cad::StepImport im = cad::import_step(path);
    ASSERT_TRUE(im.solids.at(0).solid);
    const TrimmedBoundary& b = im.solids[0].solid->boundary();
    int compared = 0;
    for (std::size_t i = 0; i < c.splines.size(); ++i) {
      if (!std::holds_alternative<TensorSpline<2>>(c.splines[i])) continue;
      const auto& ours = std::get<TensorSpline<2>>(c.splines[i]);
      for (std::uint64_t face : c.spline_info[i].faces) {
        std::string label = "#";
        label += std::to_string(face);
        label += " ADVANCED_FACE";
        const auto it = std::find_if(b.faces.begin(), b.faces.end(), [&](const TrimmedFace& f) { return f.name == label; });
        ASSERT_NE(it, b.faces.end()) << label;
        EXPECT_EQ(it->kind, "bspline");
        const Box<2> d = ours.domain(), e = it->surface.domain();
        for (int k = 0; k < 2; ++k) {
          EXPECT_DOUBLE_EQ(d.lo[k], e.lo[k]);
          EXPECT_DOUBLE_EQ(d.hi[k], e.hi[k]);
        }
        EXPECT_EQ(ours.is_rational(), it->surface.is_rational());
        double scale = 1;
        for (int s = 0; s < ours.num_coefs(); ++s) {
          double x[3];
          ours.control_point(s, x);
          scale = std::max({scale, std::abs(x[0]), std::abs(x[1]), std::abs(x[2])});
        }
        for (int a = 0; a <= 6; ++a)
          for (int q = 0; q <= 6; ++q) {
            const Param<2> u{d.lo[0] + a / 6.0 * (d.hi[0] - d.lo[0]), d.lo[1] + q / 6.0 * (d.hi[1] - d.lo[1])};
            double x[3], y[3];
            ours.eval(u, x);
            it->surface.eval(u, y);
            EXPECT_LT(std::hypot(x[0] - y[0], x[1] - y[1], x[2] - y[2]), 1e-12 * scale) << label;
          }
        ++compared;
      }
    }
    EXPECT_EQ(compared, static_cast<int>(b.faces.size()));
  }
  std::filesystem::remove_all(dir);
}
