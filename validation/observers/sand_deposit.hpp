// Shared measurements of sand deposits (column collapse, angle of repose): kinetic energy, the free
// surface as the top of the sand in columns one spacing wide.
#pragma once
#include <algorithm>
#include <cmath>
#include <vector>

#include "method/method.hpp"
#include "observers/line_fit.hpp"

namespace sc {

/// Kinetic energy of the sand particles [J] (per unit depth in 2-D).
template <int D>
double sand_kinetic_energy(const ParticleView<D>& ps) {
  double e = 0.0;
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (ps.phase_of(i) == Phase::Sand) e += 0.5 * ps.m[i] * ps.v[i].squaredNorm();
  return e;
}

/// x coordinates of the sand particles.
template <int D>
std::vector<double> sand_x(const ParticleView<D>& ps) {
  std::vector<double> out;
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (ps.phase_of(i) == Phase::Sand) out.push_back(ps.x[i][0]);
  return out;
}

/// The q-quantile (0..1) of values (nearest rank).
inline double quantile(std::vector<double> values, double q) {
  if (values.empty()) return NAN;
  std::sort(values.begin(), values.end());
  const auto k = static_cast<std::size_t>(std::clamp(std::ceil(q * values.size()) - 1.0, 0.0, values.size() - 1.0));
  return values[k];
}

/// Free surface of the sand: for columns [x0 + k dx, x0 + (k+1) dx) the height of the highest
/// sand particle plus dx/2 above `floor` (0 where a column is empty). 2-D: x is axis 0, height axis D-1.
template <int D>
std::vector<double> surface_heights(const ParticleView<D>& ps, double x0, double dx, std::size_t columns, double floor) {
  std::vector<double> top(columns, 0.0);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps.phase_of(i) != Phase::Sand) continue;
    const double k = std::floor((ps.x[i][0] - x0) / dx);
    if (k < 0.0 || k >= static_cast<double>(columns)) continue;
    auto& t = top[static_cast<std::size_t>(k)];
    t = std::max(t, ps.x[i][D - 1] - floor + 0.5 * dx);
  }
  return top;
}

}  // namespace sc
