#include "trivar/fit/scattered_data.hpp"

#include <cmath>

#include <Eigen/Eigenvalues>

#include "trivar/core/error.hpp"

namespace trivar {

template <int D>
Box<D> ScatteredData<D>::bounding_box() const {
  Box<D> b = Box<D>::empty();
  for (const Param<D>& p : params) b.extend(p.data());
  return b;
}

template <int D>
void validate(const ScatteredData<D>& data, const std::string& source, std::size_t min_points) {
  const std::size_t n = data.size();
  require(data.dim >= 1, source + ": no values per point");
  require(data.values.size() == n * static_cast<std::size_t>(data.dim),
          source + ": " + std::to_string(data.values.size()) + " values for " + std::to_string(n) + " points of " +
              std::to_string(data.dim));
  if (n == 0) throw Error(source + ": no points");
  const std::size_t need = std::max<std::size_t>(min_points, D + 1);
  require(n >= need, source + ": " + std::to_string(n) + " points, a fit needs at least " + std::to_string(need));
  for (std::size_t i = 0; i < n; ++i) {
    bool ok = true;
    for (int k = 0; k < D; ++k) ok = ok && std::isfinite(data.params[i][k]);
    for (int c = 0; c < data.dim; ++c) ok = ok && std::isfinite(data.value(i)[c]);
    require(ok, source + ": point " + std::to_string(i + 1) + " has a number that is not finite (NaN or infinity)");
  }
  // Principal axes of the parameters: a fit over a box needs points that span it.
  Eigen::Matrix<double, D, 1> mean = Eigen::Matrix<double, D, 1>::Zero();
  for (const Param<D>& p : data.params)
    for (int k = 0; k < D; ++k) mean[k] += p[k];
  mean /= static_cast<double>(n);
  Eigen::Matrix<double, D, D> cov = Eigen::Matrix<double, D, D>::Zero();
  for (const Param<D>& p : data.params) {
    Eigen::Matrix<double, D, 1> d;
    for (int k = 0; k < D; ++k) d[k] = p[k] - mean[k];
    cov.noalias() += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, D, D>> eig(cov, Eigen::EigenvaluesOnly);
  const auto& ev = eig.eigenvalues();  // ascending
  const double largest = ev[D - 1];
  require(largest > 0.0 && ev[0] > 1e-10 * largest,
          source + (D == 2 ? ": all points lie on a line" : ": all points lie on a plane or a line") +
              " (a fit needs points that span the " + (D == 2 ? "x-y rectangle)" : "box)"));
}

template <int D>
ScatteredData<D> scattered_data(const PointTable& table, const std::string& source, std::size_t min_points) {
  require(table.columns >= D + 1, source + ": " + std::to_string(table.columns) + " column" +
                                      (table.columns == 1 ? "" : "s") + " per point, a fit over " +
                                      std::to_string(D) + " coordinates needs at least " + std::to_string(D + 1));
  ScatteredData<D> data;
  data.dim = table.columns - D;
  const std::size_t n = table.rows();
  data.params.resize(n);
  data.values.resize(n * static_cast<std::size_t>(data.dim));
  for (std::size_t i = 0; i < n; ++i) {
    const double* row = table.values.data() + i * static_cast<std::size_t>(table.columns);
    for (int k = 0; k < D; ++k) data.params[i][k] = row[k];
    for (int c = 0; c < data.dim; ++c) data.values[i * static_cast<std::size_t>(data.dim) + static_cast<std::size_t>(c)] = row[D + c];
  }
  validate(data, source, min_points);
  return data;
}

template struct ScatteredData<2>;
template struct ScatteredData<3>;
template void validate(const ScatteredData<2>&, const std::string&, std::size_t);
template void validate(const ScatteredData<3>&, const std::string&, std::size_t);
template ScatteredData<2> scattered_data(const PointTable&, const std::string&, std::size_t);
template ScatteredData<3> scattered_data(const PointTable&, const std::string&, std::size_t);

}  // namespace trivar
