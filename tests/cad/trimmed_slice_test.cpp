// Slicing a trimmed model: inside pixels follow the trimmed boundary (checked against OpenCASCADE's
// classification of the pixel centres), materials come from the cell's attribute.
#include <gtest/gtest.h>

#include <BRepClass3d_SolidClassifier.hxx>
#include <unistd.h>

#include "cad/occt_solids.hpp"
#include "trivar/am/layer_slicer.hpp"
#include "trivar/am/slicer.hpp"
#include "trivar/cad/step_import.hpp"

using namespace trivar;

TEST(TrimmedSlice, InsidePixelsFollowTheTrimmedBoundary) {
  const auto dir = test::temp_dir("slice");
  const TopoDS_Shape shape = test::box_with_holes();
  const cad::StepImport im = cad::import_step(test::write_step(shape, dir, "part"));
  const auto& solid = im.solids.at(0).solid;
  Box<3> box = solid->bounding_box();
  std::vector<double> pts;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) pts.insert(pts.end(), {i ? box.hi[0] : box.lo[0], j ? box.hi[1] : box.lo[1], k ? box.hi[2] : box.lo[2]});
  const TensorSpline<3> cube = TensorSpline<3>::from_cartesian(
      {KnotVector::open_uniform(1, 1, box.lo[0], box.hi[0]), KnotVector::open_uniform(1, 1, box.lo[1], box.hi[1]),
       KnotVector::open_uniform(1, 1, box.lo[2], box.hi[2])},
      3, pts);
  VModel m;
  VCell cell(cube, solid);
  // Two materials blending along x.
  cell.set_attribute("material", Attribute::expression({"min(1, max(0, x / 40))", "1 - min(1, max(0, x / 40))"}, Attribute::Space::model));
  m.add_cell(std::move(cell));
  m.glue();
  am::SliceOptions o;
  o.layer_thickness = 10;
  o.z_range = std::array<double, 2>{0, 20};
  o.dpi_x = o.dpi_y = 25.4 / 0.25;  // 0.25 mm pixels
  am::SliceSummary sum;
  const std::vector<am::SliceLayer> layers = am::slice_model(m, o, &sum);
  ASSERT_EQ(layers.size(), 2u);
  const am::SliceGrid g = am::slice_grid(m, o);
  std::int64_t disagree = 0, inside = 0;
  for (const am::SliceLayer& L : layers)
    for (int j = 0; j < L.height; ++j)
      for (int i = 0; i < L.width; ++i) {
        const bool in = L.owner(i, j) == 0;
        inside += in;
        if ((i + 2 * j) % 4 == 0) {  // a quarter of the centres, for time
          BRepClass3d_SolidClassifier c(shape, gp_Pnt(g.x(i), g.y(j), L.z), 1e-7);
          if (c.State() != TopAbs_ON && in != (c.State() == TopAbs_IN)) ++disagree;
        }
        if (in) {
          EXPECT_NEAR(L.fractions.pixel(i, j)[0], g.x(i) / 40, 1e-6);
          EXPECT_NEAR(L.fractions.pixel(i, j)[1], 1 - g.x(i) / 40, 1e-6);
        }
      }
  EXPECT_EQ(disagree, 0);
  EXPECT_EQ(inside, sum.inside_pixels);
  // The inside area per layer is the cross-section's, to the pixel resolution.
  const double area = 40.0 * 30 - 2 * test::kPi * 16;
  EXPECT_NEAR(static_cast<double>(inside) / 2 * g.dx * g.dy, area, 0.01 * area);
  std::filesystem::remove_all(dir);
}
