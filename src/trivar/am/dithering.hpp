#pragma once
// Dithering of one layer: desired material fractions per pixel -> exactly one material per pixel, so that the
// local density of every material follows its fraction. Layers are independent and the result depends only on
// the input (no threads, no randomness inside), so a slicer may dither layers in parallel and still write
// identical files for any thread count.
//
// Input pixels: the fractions of a pixel are clamped to [0, 1] and divided by their sum; a pixel whose clamped
// sum is 0 is outside the part and gets empty_label. A NaN fraction is an error.
#include "trivar/core/layer_image.hpp"

namespace trivar::am {

enum class DitherMethod {
  // N-material vector error diffusion (Floyd-Steinberg weights 7/16, 3/16, 5/16, 1/16, serpentine scan): the
  // chosen material is the one whose unit vector is nearest to desired + accumulated error, i.e. its largest
  // component (ties to the lower index). The m-vector error goes only to neighbours inside the part, with the
  // weights of the admitted neighbours rescaled to sum 1, so material is conserved up to the error left at
  // pixels without any inside neighbour ahead (O(perimeter), a single pixel for a full rectangle). Error never
  // leaks across the part boundary into empty pixels, which would bias the edge material.
  error_diffusion,
  // Ordered dithering with a Bayer matrix: threshold t = (B(x mod n, y mod n) + 1/2) / n^2 and the pixel takes
  // the first material whose cumulative fraction exceeds t. Exact fractions on every n x n tile for fractions
  // that are multiples of 1/n^2; no error transport, so the material edges follow the field without lag.
  ordered,
};

struct DitherOptions {
  DitherMethod method = DitherMethod::error_diffusion;
  int bayer_size = 16;  // 2, 4, 8 or 16 (ordered dithering only)
};

// One label per pixel (empty_label outside, k + 1 for material k). Throws trivar::Error for more than 255
// materials, a bad Bayer size or a NaN fraction.
LabelImage dither(const FractionImage& fractions, const DitherOptions& options = {});

// As above into `labels` (resized), so a caller dithering many layers reuses one buffer.
void dither(const FractionImage& fractions, LabelImage& labels, const DitherOptions& options = {});

// Bayer index matrix of size n (power of two, 2..16), entries 0..n^2-1, row-major: entry [y * n + x].
const int* bayer_matrix(int n);

}  // namespace trivar::am
