#pragma once
// Bernstein<D>: a scalar polynomial in D variables on the unit box [0,1]^D, in the tensor-product Bernstein
// basis, f(t) = sum_i c_i prod_k C(n_k, i_k) t_k^i_k (1 - t_k)^(n_k - i_k). It is the exact arithmetic of the
// Jacobian check: products, sums and derivatives of Bezier nets stay in Bernstein form, and the coefficients
// bound the values (convex hull), with the corner coefficients equal to the corner values.
#include <span>
#include <utility>
#include <vector>

#include "trivar/core/box.hpp"

namespace trivar {

template <int D>
class Bernstein {
  static_assert(D >= 1 && D <= 3, "Bernstein supports 1 to 3 variables");

public:
  Bernstein() = default;
  // The constant `value` written with degrees n (every coefficient equals the value).
  explicit Bernstein(const Ints<D>& degrees, double value = 0.0);
  // coefs: prod(n_k + 1) values, first variable fastest. Throws trivar::Error on a size mismatch or a
  // negative degree.
  Bernstein(const Ints<D>& degrees, std::vector<double> coefs);

  const Ints<D>& degrees() const { return n_; }
  int degree(int k) const { return n_[k]; }
  int size() const { return static_cast<int>(c_.size()); }
  std::span<const double> coefs() const { return c_; }
  std::span<double> coefs() { return c_; }
  // Coefficient with multi-index i.
  double coef(const Ints<D>& i) const { return c_[index(i)]; }
  int index(const Ints<D>& i) const;

  // Value at t in [0,1]^D (Bernstein sums; no allocation after the first call on a thread).
  double eval(const Param<D>& t) const;
  double min_coef() const;
  double max_coef() const;
  // Value at a corner of the unit box: bit k of `corner` selects t_k = 1, otherwise t_k = 0. It is a
  // coefficient, so exact.
  double corner(int corner) const;

  // The same polynomial written with degrees `to` (to[k] >= degree(k)).
  Bernstein elevate(const Ints<D>& to) const;
  // Partial derivative with respect to t_dir: degree n_dir - 1 with coefficients n (c_{i+1} - c_i); the
  // derivative of a polynomial of degree 0 in dir is the zero polynomial of degree 0 there.
  Bernstein derivative(int dir) const;
  // de Casteljau at t_dir = t: the pieces on [0, t] and [t, 1] of direction dir, each reparametrised to [0, 1].
  std::pair<Bernstein, Bernstein> subdivide(int dir, double t) const;
  // Largest difference of neighbouring coefficients along direction dir: how much f varies in that direction.
  double variation(int dir) const;

  Bernstein& operator*=(double s);

private:
  Ints<D> n_{};
  std::vector<double> c_;
};

// Product of degree n + m: coefficient (i + j) gathers c_i d_j C(n,i) C(m,j) / C(n+m, i+j) per direction.
template <int D>
Bernstein<D> operator*(const Bernstein<D>& a, const Bernstein<D>& b);
// Sum and difference, both operands raised to the common degree max(n_k, m_k) first.
template <int D>
Bernstein<D> operator+(const Bernstein<D>& a, const Bernstein<D>& b);
template <int D>
Bernstein<D> operator-(const Bernstein<D>& a, const Bernstein<D>& b);

extern template class Bernstein<1>;
extern template class Bernstein<2>;
extern template class Bernstein<3>;

}  // namespace trivar
