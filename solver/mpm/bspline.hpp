// Quadratic B-spline interpolation between MPM particles and grid nodes (Jiang et al. 2016, the MPM
// course notes, §9.3; Tampubolon et al. 2017 use the same weights): each particle reaches the 3^D
// nodes nearest to it, with weights that sum to one and reproduce linear functions.
#pragma once
#include <array>
#include <cmath>

#include "core/types.hpp"

namespace sc::mpm {

/// The 1-D quadratic B-spline N(r) of the distance r between a particle and a node in cell widths:
/// 3/4 − r² for |r| < 1/2, (3/2 − |r|)²/2 for 1/2 ≤ |r| < 3/2, 0 beyond.
/// [Jiang 2016: quadratic B-spline]
inline double bspline(double r) {
  const double a = std::abs(r);
  if (a < 0.5) return 0.75 - a * a;
  if (a < 1.5) return 0.5 * (1.5 - a) * (1.5 - a);
  return 0.0;
}

/// The 1-D weights of a particle along each axis: [d][k] = N((x_p − x_{b+k})_d / h) for the three
/// nodes b, b + 1, b + 2 of its stencil (b its base node, Grid::base).
template <int D>
using AxisWeights = std::array<std::array<double, 3>, D>;

/// The weight w_ip = Π_d N((x_p − x_i)_d / h) of a particle and the node at `offset` (0, 1 or 2 per
/// axis) in its stencil. [Jiang 2016: tensor-product weights]
template <int D>
double weight(const AxisWeights<D>& axes, const std::array<int, D>& offset) {
  double w = 1.0;
  for (int d = 0; d < D; ++d) w *= axes[d][offset[d]];
  return w;
}

/// The inverse of the APIC inertia tensor of the quadratic B-spline, D_p⁻¹ = (4/h²) I, as a scalar.
/// [Jiang 2015: APIC, D_p of quadratic weights]
inline double inertia_inverse(double h) { return 4.0 / (h * h); }

}  // namespace sc::mpm
