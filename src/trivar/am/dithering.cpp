#include "trivar/am/dithering.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "trivar/core/error.hpp"

namespace trivar::am {

namespace {

template <int N>
std::array<int, N * N> make_bayer() {
  std::array<int, N * N> m{};
  if constexpr (N == 1) {
    m[0] = 0;
  } else {
    // M_2n = [[4M, 4M+2], [4M+3, 4M+1]] (Bayer's recursive construction).
    constexpr int h = N / 2;
    const auto half = make_bayer<h>();
    constexpr int offset[2][2] = {{0, 2}, {3, 1}};
    for (int y = 0; y < N; ++y)
      for (int x = 0; x < N; ++x) m[y * N + x] = 4 * half[(y % h) * h + x % h] + offset[y / h][x / h];
  }
  return m;
}

// Clamps the fractions of one pixel to [0, 1] into `out`; returns their sum (0 = outside the part).
double clamp_pixel(const float* f, int m, double* out, int x, int y) {
  double sum = 0;
  for (int k = 0; k < m; ++k) {
    const float v = f[k];
    require(!std::isnan(v), [&] {
      return "dither: fraction " + std::to_string(k) + " of pixel (" + std::to_string(x) + ", " + std::to_string(y) +
             ") is NaN";
    });
    out[k] = std::clamp(static_cast<double>(v), 0.0, 1.0);
    sum += out[k];
  }
  return sum;
}

// Normalised fractions of row y into `desired` (W x m) and the inside flags into `inside`.
template <int M>
void load_row(const FractionImage& in, int y, std::vector<double>& desired, std::vector<unsigned char>& inside) {
  const int m = M > 0 ? M : in.channels();
  for (int x = 0; x < in.width(); ++x) {
    double* d = desired.data() + static_cast<std::size_t>(x) * static_cast<std::size_t>(m);
    const double sum = clamp_pixel(in.pixel(x, y), m, d, x, y);
    inside[static_cast<std::size_t>(x)] = sum > 0;
    if (sum > 0)
      for (int k = 0; k < m; ++k) d[k] /= sum;
  }
}

// M > 0 fixes the material count at compile time so the per-pixel loops unroll (the common 2..4 materials);
// M = 0 reads it from the image.
template <int M>
void error_diffusion(const FractionImage& in, LabelImage& out) {
  const int w = in.width(), h = in.height(), m = M > 0 ? M : in.channels();
  const auto row_size = static_cast<std::size_t>(w) * static_cast<std::size_t>(m);
  std::vector<double> desired(row_size), desired_next(row_size), err(row_size, 0.0), err_next(row_size, 0.0);
  std::vector<unsigned char> inside(static_cast<std::size_t>(w)), inside_next(static_cast<std::size_t>(w));
  std::vector<double> v(static_cast<std::size_t>(m));
  if (h > 0) load_row<M>(in, 0, desired, inside);

  for (int y = 0; y < h; ++y) {
    const bool has_next = y + 1 < h;
    if (has_next) load_row<M>(in, y + 1, desired_next, inside_next);
    // Serpentine: even rows left to right, odd rows right to left, so the error does not drift to one side.
    const int dir = y % 2 == 0 ? 1 : -1;
    const int x0 = dir > 0 ? 0 : w - 1;
    for (int i = 0, x = x0; i < w; ++i, x += dir) {
      std::uint8_t* label = out.pixel(x, y);
      if (!inside[static_cast<std::size_t>(x)]) {
        *label = empty_label;
        continue;
      }
      const std::size_t base = static_cast<std::size_t>(x) * static_cast<std::size_t>(m);
      int best = 0;
      for (int k = 0; k < m; ++k) {
        v[static_cast<std::size_t>(k)] = desired[base + static_cast<std::size_t>(k)] + err[base + static_cast<std::size_t>(k)];
        if (v[static_cast<std::size_t>(k)] > v[static_cast<std::size_t>(best)]) best = k;
      }
      *label = static_cast<std::uint8_t>(best + 1);
      v[static_cast<std::size_t>(best)] -= 1.0;

      // Floyd-Steinberg neighbours (ahead on this row, then below-behind, below, below-ahead), inside only.
      const int xa = x + dir, xb = x - dir;
      const bool ahead_in = xa >= 0 && xa < w;
      const bool behind_in = xb >= 0 && xb < w;
      const double w_ahead = ahead_in && inside[static_cast<std::size_t>(xa)] ? 7.0 : 0.0;
      const double w_bl = has_next && behind_in && inside_next[static_cast<std::size_t>(xb)] ? 3.0 : 0.0;
      const double w_b = has_next && inside_next[static_cast<std::size_t>(x)] ? 5.0 : 0.0;
      const double w_ba = has_next && ahead_in && inside_next[static_cast<std::size_t>(xa)] ? 1.0 : 0.0;
      const double total = w_ahead + w_bl + w_b + w_ba;
      if (total == 0) continue;  // no inside pixel ahead: this residual is the only material not conserved
      const double s = 1.0 / total;
      auto spread = [&](std::vector<double>& e, int xt, double wt) {
        if (wt == 0) return;
        double* t = e.data() + static_cast<std::size_t>(xt) * static_cast<std::size_t>(m);
        const double f = wt * s;
        for (int k = 0; k < m; ++k) t[k] += f * v[static_cast<std::size_t>(k)];
      };
      spread(err, xa, w_ahead);
      spread(err_next, xb, w_bl);
      spread(err_next, x, w_b);
      spread(err_next, xa, w_ba);
    }
    desired.swap(desired_next);
    inside.swap(inside_next);
    err.swap(err_next);
    std::fill(err_next.begin(), err_next.end(), 0.0);
  }
}

void ordered(const FractionImage& in, LabelImage& out, int n) {
  const int* b = bayer_matrix(n);
  const int m = in.channels();
  const double cells = static_cast<double>(n) * n;
  std::vector<double> c(static_cast<std::size_t>(m));
  for (int y = 0; y < in.height(); ++y)
    for (int x = 0; x < in.width(); ++x) {
      const double sum = clamp_pixel(in.pixel(x, y), m, c.data(), x, y);
      std::uint8_t* label = out.pixel(x, y);
      if (sum <= 0) {
        *label = empty_label;
        continue;
      }
      // First material whose cumulative (unnormalised) fraction exceeds t * sum; rounding cannot push the
      // choice past the last material with a non-zero fraction.
      const double t = (b[(y % n) * n + x % n] + 0.5) / cells * sum;
      double cumulative = 0;
      int chosen = -1, last_present = 0;
      for (int k = 0; k < m; ++k) {
        if (c[static_cast<std::size_t>(k)] <= 0) continue;
        last_present = k;
        cumulative += c[static_cast<std::size_t>(k)];
        if (cumulative > t) {
          chosen = k;
          break;
        }
      }
      *label = static_cast<std::uint8_t>((chosen >= 0 ? chosen : last_present) + 1);
    }
}

}  // namespace

const int* bayer_matrix(int n) {
  static const auto b2 = make_bayer<2>();
  static const auto b4 = make_bayer<4>();
  static const auto b8 = make_bayer<8>();
  static const auto b16 = make_bayer<16>();
  switch (n) {
    case 2: return b2.data();
    case 4: return b4.data();
    case 8: return b8.data();
    case 16: return b16.data();
    default: throw Error("bayer_matrix: size " + std::to_string(n) + " is not 2, 4, 8 or 16");
  }
}

void dither(const FractionImage& fractions, LabelImage& labels, const DitherOptions& options) {
  require(fractions.channels() <= 255,
          "dither: " + std::to_string(fractions.channels()) + " materials exceed the 255 labels of a byte");
  if (options.method == DitherMethod::ordered) bayer_matrix(options.bayer_size);  // validates before any work
  if (labels.width() != fractions.width() || labels.height() != fractions.height() || labels.channels() != 1)
    labels = LabelImage(fractions.width(), fractions.height());
  if (options.method == DitherMethod::error_diffusion) switch (fractions.channels()) {
      case 2: error_diffusion<2>(fractions, labels); break;
      case 3: error_diffusion<3>(fractions, labels); break;
      case 4: error_diffusion<4>(fractions, labels); break;
      default: error_diffusion<0>(fractions, labels);
    }
  else
    ordered(fractions, labels, options.bayer_size);
}

LabelImage dither(const FractionImage& fractions, const DitherOptions& options) {
  LabelImage labels;
  dither(fractions, labels, options);
  return labels;
}

}  // namespace trivar::am
