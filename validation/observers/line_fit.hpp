// Straight-line fits shared by the observers.
#pragma once
#include <cmath>
#include <vector>

namespace sc {

/// Least-squares slope of y against x (NaN when every x is equal).
inline double fitted_slope(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = static_cast<double>(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    sx += x[k]; sy += y[k]; sxx += x[k] * x[k]; sxy += x[k] * y[k];
  }
  const double den = n * sxx - sx * sx;
  return den != 0.0 ? (n * sxy - sx * sy) / den : NAN;
}

}  // namespace sc
