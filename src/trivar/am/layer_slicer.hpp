#pragma once
// Slicing of one layer: outlines of the cells at z -> pixels inside -> (u, v, w) of every inside pixel by
// point inversion with tracing -> material fractions.
//
// Pixels inside (scanline fill): for each row, the crossings of the row's centre line with a cell's outline
// segments (half-open in y, so a vertex on the line counts once) are sorted and paired by the even-odd rule;
// a pixel is claimed by the cell when its centre x lies in [x_in, x_out). The same fill over the segments of
// the MODEL's boundary faces (cell faces without a twin) marks the pixels inside the part.
//
// Ownership rule where cells touch: a pixel belongs to the first cell in index order that claims it and in
// which its centre is found by point inversion. When that cell's inversion rejects the centre (a chord of a
// shared face bulged over it) or no cell claims a centre that lies inside the part (the two chords of a
// shared face left a sliver), the other cells whose bounding box contains the centre are searched in index
// order and the first that contains it takes it (LayerStats::corrected_pixels); when none does, the pixel is
// outside. So a pixel is never counted twice, and a centre in the part is never left out unless the model's
// own outline excludes it.
//
// Tracing (per row, left to right; SliceOptions::tracing selects the sources): Newton starts from the
// parameters of the pixels to the left in the same cell, extrapolated (by the polynomial through up to five
// of them) and refined by chord steps that reuse the last solved pixel's inverse Jacobian (one value evaluation
// per step, on the cell's element polynomials where its degrees have them, spline/element_polynomials.hpp:
// they differ from TensorSpline::eval by about 1e-12 of the cell's size, far below the inversion tolerance,
// so a fraction can differ from the B-spline path's in its last float bit); where the row enters the cell,
// from the parameters of the outline crossing there; else from the pixel below or the nearest pixel of the
// cell on the previous row. These Newton solves iterate on the element polynomials too (the damped iteration
// of PointInverter::newton with an explicit 3 x 3 inverse; PointInverter::newton itself where that fails). The
// robust subdivision search (PointInverter::invert) runs only when these fail or none exists. Each row's loop
// covers only the extent its spans painted. Rows are processed bottom-up within a layer and no state crosses layers, so layers are
// independent.
#include <vector>

#include "trivar/am/cell_section.hpp"
#include "trivar/am/slice_layer.hpp"
#include "trivar/am/slice_options.hpp"
#include "trivar/model/vmodel.hpp"
#include "trivar/spline/element_polynomials.hpp"
#include "trivar/spline/point_inversion.hpp"

namespace trivar::am {

class LayerSlicer {
public:
  // Validates the options against the model and precomputes the per-cell data. The model must outlive the
  // slicer and keep its cells and attributes unchanged. Throws trivar::Error for a non-positive or
  // non-finite thickness, dpi, image size, tolerance or sample count, an empty z range, an unglued or empty
  // model, a named material attribute no cell has, a material attribute present on only some cells or with
  // differing component counts, or a material table whose size differs from the attribute's components.
  LayerSlicer(const VModel& model, const SliceOptions& options);

  const SliceGrid& grid() const { return grid_; }
  // Number of material channels of the fractions (1 when the model has no material attribute).
  int materials() const { return materials_; }

  // Slices layer k (0 <= k < grid().layers). Thread-safe: layers may be sliced concurrently.
  SliceLayer slice(int k) const;
  // The same into `layer`, reusing its images when they have this grid's size and channels and their
  // row_extents: only the pixels written before are cleared (the ball of radius 20 on the 2944 x 1466 tray
  // fills a tenth of it), and no new 50 MB of pages are faulted in per layer. The result equals slice(k) when
  // `layer` is default, had its images moved out, or came from a slicer of the same grid and materials and
  // its pixels were not changed since outside its row_extents.
  void slice(int k, SliceLayer& layer) const;
  // The outline of cell c at height z (segments of its six faces), as the fill uses it.
  void outline(int c, double z, std::vector<OutlineSegment>& out) const { sections_[static_cast<std::size_t>(c)].section(z, out); }

private:
  const VModel& model_;
  SliceOptions options_;
  SliceGrid grid_;
  std::vector<CellSection> sections_;
  std::vector<PointInverter<3>> inverters_;
  std::vector<ElementPolynomials> polynomials_;   // per cell, for the chord steps' value evaluations
  std::vector<Box<3>> boxes_;                     // control-point box per cell, for the correction search
  std::vector<Box<3>> domains_;                 // parameter domain per cell
  std::vector<std::array<bool, 6>> model_face_;   // face on the model boundary (no twin)
  std::vector<const Attribute*> material_;        // per cell, null when the model has no material attribute
  int materials_ = 1;
};

// The options resolved against the model's bounding box (see slice_options.hpp); validates as above.
SliceGrid slice_grid(const VModel& model, const SliceOptions& options);

}  // namespace trivar::am
