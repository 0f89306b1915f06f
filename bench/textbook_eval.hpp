#pragma once
// A textbook B-spline volume evaluation (Piegl & Tiller, The NURBS Book, A2.1 FindSpan by bisection, A2.2
// BasisFuns with divisions, then the triple sum over the (p+1)^3 active control points), without allocation:
// the machine-independent yardstick the evaluation benchmark compares trivar's kernels with.
#include <array>
#include <vector>

namespace trivar::bench {

class TextbookVolume {
public:
  TextbookVolume(int p, std::array<std::vector<double>, 3> knots, std::vector<double> points)
      : p_(p), t_(std::move(knots)), cp_(std::move(points)) {
    for (int k = 0; k < 3; ++k) n_[k] = static_cast<int>(t_[k].size()) - p_ - 1;
  }

  void eval(const std::array<double, 3>& u, double* x) const {
    constexpr int kMax = 8;
    double N[3][kMax];
    int span[3];
    for (int k = 0; k < 3; ++k) {
      span[k] = find_span(t_[k], n_[k], u[k]);
      basis_funs(t_[k], span[k], u[k], N[k]);
    }
    x[0] = x[1] = x[2] = 0.0;
    for (int c = 0; c <= p_; ++c)
      for (int b = 0; b <= p_; ++b)
        for (int a = 0; a <= p_; ++a) {
          const int i = span[0] - p_ + a, j = span[1] - p_ + b, l = span[2] - p_ + c;
          const double* q = cp_.data() + 3 * (i + n_[0] * (j + n_[1] * l));
          const double w = N[0][a] * N[1][b] * N[2][c];
          for (int d = 0; d < 3; ++d) x[d] += w * q[d];
        }
  }

private:
  int find_span(const std::vector<double>& t, int n, double u) const {
    if (u >= t[n]) return n - 1;
    int low = p_, high = n, mid = (low + high) / 2;
    while (u < t[mid] || u >= t[mid + 1]) {
      if (u < t[mid]) high = mid;
      else low = mid;
      mid = (low + high) / 2;
    }
    return mid;
  }
  void basis_funs(const std::vector<double>& t, int s, double u, double* N) const {
    double left[8], right[8];
    N[0] = 1.0;
    for (int j = 1; j <= p_; ++j) {
      left[j] = u - t[s + 1 - j];
      right[j] = t[s + j] - u;
      double saved = 0.0;
      for (int r = 0; r < j; ++r) {
        const double tmp = N[r] / (right[r + 1] + left[j - r]);
        N[r] = saved + right[r + 1] * tmp;
        saved = left[j - r] * tmp;
      }
      N[j] = saved;
    }
  }

  int p_;
  std::array<std::vector<double>, 3> t_;
  std::vector<double> cp_;
  std::array<int, 3> n_{};
};

}  // namespace trivar::bench
