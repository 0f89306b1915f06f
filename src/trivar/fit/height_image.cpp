#include "trivar/fit/height_image.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "trivar/core/error.hpp"

namespace trivar {
namespace {

using Rgb = std::array<double, 3>;

// Piecewise-linear ramp through (position, colour) stops, position in [0, 1].
template <std::size_t N>
Rgb ramp(const std::array<std::pair<double, Rgb>, N>& stops, double t) {
  t = std::clamp(t, 0.0, 1.0);
  for (std::size_t i = 1; i < N; ++i)
    if (t <= stops[i].first) {
      const double s = (t - stops[i - 1].first) / (stops[i].first - stops[i - 1].first);
      Rgb c;
      for (int k = 0; k < 3; ++k) c[k] = (1 - s) * stops[i - 1].second[k] + s * stops[i].second[k];
      return c;
    }
  return stops[N - 1].second;
}

void put(LayerImage<std::uint8_t>& img, int x, int y, const Rgb& c, double shade = 1.0) {
  for (int k = 0; k < 3; ++k) img(x, y, k) = static_cast<std::uint8_t>(std::lround(std::clamp(c[k] * shade, 0.0, 1.0) * 255));
}

std::pair<int, int> image_size(double w, double h, int width) {
  require(width >= 1 && width <= 16384, "fit: image width " + std::to_string(width) + " outside 1..16384");
  const int height = std::clamp(static_cast<int>(std::lround(width * h / w)), 1, 16384);
  return {width, height};
}

}  // namespace

LayerImage<std::uint8_t> height_image(const LRSpline<2>& s, int width, int threads) {
  const Box<2>& dom = s.domain();
  const auto [nx, ny] = image_size(dom.hi[0] - dom.lo[0], dom.hi[1] - dom.lo[1], width);
  const double dx = (dom.hi[0] - dom.lo[0]) / nx, dy = (dom.hi[1] - dom.lo[1]) / ny;
  std::vector<Param<2>> u(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny));
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x) u[static_cast<std::size_t>(y) * nx + x] = {dom.lo[0] + (x + 0.5) * dx, dom.lo[1] + (y + 0.5) * dy};
  const int dim = s.dim();
  std::vector<double> v(u.size() * 3 * static_cast<std::size_t>(dim));
  s.eval_first_derivatives_many(u, v, threads);
  // The height is the last component; for a graph (x, y, z) its slopes are dz/du over dx/du.
  auto height = [&](std::size_t i, int part) { return v[(i * 3 + static_cast<std::size_t>(part)) * dim + dim - 1]; };
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (std::size_t i = 0; i < u.size(); ++i) {
    lo = std::min(lo, height(i, 0));
    hi = std::max(hi, height(i, 0));
  }
  const double range = hi > lo ? hi - lo : 1.0;
  // Slopes are exaggerated so the relief shows at any height range: the steepest slope of the picture is ~45 deg
  // for a range spread over a fifth of the width.
  const double exaggeration = 0.2 * (dom.hi[0] - dom.lo[0]) / range;
  static const std::array<std::pair<double, Rgb>, 6> terrain = {{{0.0, {0.2, 0.3, 0.6}},
                                                                  {0.15, {0.0, 0.6, 0.9}},
                                                                  {0.3, {0.1, 0.7, 0.35}},
                                                                  {0.55, {0.95, 0.9, 0.55}},
                                                                  {0.8, {0.55, 0.4, 0.3}},
                                                                  {1.0, {1.0, 1.0, 1.0}}}};
  const double light[3] = {-0.5, 0.5, 0.7071067811865476};  // from the north-west, 45 degrees up
  LayerImage<std::uint8_t> img(nx, ny, 3);
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * nx + x;
      double gx = height(i, 1), gy = height(i, 2);
      if (dim == 3) {  // a graph: chain rule with x(u), y(v)
        const double xu = v[(i * 3 + 1) * 3 + 0], yv = v[(i * 3 + 2) * 3 + 1];
        gx = xu != 0.0 ? gx / xu : 0.0;
        gy = yv != 0.0 ? gy / yv : 0.0;
      }
      const double nxv = -gx * exaggeration, nyv = -gy * exaggeration;
      const double len = std::sqrt(nxv * nxv + nyv * nyv + 1.0);
      const double lambert = std::max(0.0, (nxv * light[0] + nyv * light[1] + light[2]) / len);
      put(img, x, y, ramp(terrain, (height(i, 0) - lo) / range), 0.55 + 0.45 * lambert);
    }
  return img;
}

LayerImage<std::uint8_t> error_image(const ScatteredData<2>& data, std::span<const double> errors, double tolerance,
                                     int width) {
  require(errors.size() == data.size(), "fit: " + std::to_string(errors.size()) + " errors for " +
                                             std::to_string(data.size()) + " points");
  require(tolerance > 0.0, "fit: the error picture needs a positive tolerance");
  const Box<2> box = data.bounding_box();
  const double w = std::max(box.hi[0] - box.lo[0], 1e-300), h = std::max(box.hi[1] - box.lo[1], 1e-300);
  const auto [nx, ny] = image_size(w, h, width);
  // Bins of about four points each (at most one per pixel), so sparse data shows as areas, not speckles.
  const double per_bin = std::max(1.0, static_cast<double>(data.size()) / 4.0);
  const int bx = std::clamp(static_cast<int>(std::lround(std::sqrt(per_bin * w / h))), 1, nx);
  const int by = std::clamp(static_cast<int>(std::lround(std::sqrt(per_bin * h / w))), 1, ny);
  std::vector<double> bins(static_cast<std::size_t>(bx) * static_cast<std::size_t>(by), -1.0);
  for (std::size_t i = 0; i < data.size(); ++i) {
    const int x = std::clamp(static_cast<int>((data.params[i][0] - box.lo[0]) / w * bx), 0, bx - 1);
    const int y = std::clamp(static_cast<int>((data.params[i][1] - box.lo[1]) / h * by), 0, by - 1);
    double& c = bins[static_cast<std::size_t>(y) * bx + x];
    c = std::max(c, errors[i]);
  }
  std::vector<double> worst(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny));
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x)
      worst[static_cast<std::size_t>(y) * nx + x] =
          bins[static_cast<std::size_t>(y * by / ny) * bx + static_cast<std::size_t>(x * bx / nx)];
  static const std::array<std::pair<double, Rgb>, 4> heat = {
      {{0.0, {1.0, 1.0, 1.0}}, {0.4, {1.0, 0.95, 0.3}}, {0.75, {1.0, 0.55, 0.1}}, {1.0, {0.85, 0.05, 0.05}}}};
  LayerImage<std::uint8_t> img(nx, ny, 3);
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x) {
      const double e = worst[static_cast<std::size_t>(y) * nx + x];
      if (e < 0.0) put(img, x, y, {0.75, 0.75, 0.75});
      else if (e > tolerance) put(img, x, y, {0.45, 0.0, 0.55});
      else put(img, x, y, ramp(heat, e / tolerance));
    }
  return img;
}

}  // namespace trivar
