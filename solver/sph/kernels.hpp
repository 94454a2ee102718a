// Smoothing kernels of Müller, Charypar & Gross 2003 in 2-D and 3-D, with the exact constants of
// docs/equations.md §1 (each derived from the normalisation ∫W dV = 1).
//
// Conventions (docs/equations.md §0): `d` is x_i - x_j and r = |d|. Every gradient is the gradient with
// respect to x_i, gradW_ij = W'(r) d / r, which points from i towards j (W' < 0). All kernels vanish
// for r >= h.
//
// Usage (as in Müller 2003): poly6 for density and scalar interpolation, the spiky gradient for
// pressure, the viscosity Laplacian for viscosity.
#pragma once
#include <cmath>

#include "core/types.hpp"

namespace sc::kernel {

/// The normalisation constant `constant(h)` of one kernel, remembered per thread for the last
/// kRemembered distinct h seen: all particles of a uniform scene share h, an adaptive scene has a
/// few per level (split and merge round h a few ulps apart), and std::pow with the division costs
/// more than the rest of a kernel evaluation. With one slot, the pairs across levels (whose terms
/// evaluate the kernel at both h_i and h_j) would evict it at every call. The value is computed by
/// the same expression, so results do not depend on the cache. (Each call site passes its own lambda, hence
/// its own cache.)
inline constexpr int kRemembered = 4;
template <class F>
inline double remembered(double h, F&& constant) {
  struct Slots {
    double h[kRemembered] = {NAN, NAN, NAN, NAN};
    double c[kRemembered] = {};
    int next = 0;
  };
  thread_local Slots s;
  for (int k = 0; k < kRemembered; ++k)
    if (s.h[k] == h) return s.c[k];
  const int k = s.next;
  s.next = (k + 1) % kRemembered;
  s.h[k] = h;
  s.c[k] = constant(h);
  return s.c[k];
}

/// The normalisation constants of the kernels at support h (remembered, see above).
namespace constant {
template <int D>
inline double poly6(double h) {
  return remembered(h, [](double s) { return D == 3 ? 315.0 / (64.0 * pi * std::pow(s, 9)) : 4.0 / (pi * std::pow(s, 8)); });
}
template <int D>
inline double spiky(double h) {
  return remembered(h, [](double s) { return D == 3 ? 15.0 / (pi * std::pow(s, 6)) : 10.0 / (pi * std::pow(s, 5)); });
}
template <int D>
inline double spiky_derivative(double h) {
  return remembered(h, [](double s) { return D == 3 ? -45.0 / (pi * std::pow(s, 6)) : -30.0 / (pi * std::pow(s, 5)); });
}
template <int D>
inline double viscosity_laplacian(double h) {
  return remembered(h, [](double s) { return D == 3 ? 45.0 / (pi * std::pow(s, 6)) : 40.0 / (pi * std::pow(s, 5)); });
}
}  // namespace constant

/// A support h with the kernel constants at it, looked up once: a loop over the pairs of particle
/// i builds Support(h_i) before the loop and passes it to the kernels below, which then skip the
/// remembered search. Same values, same bits as the forms taking h. Converts from h, so a single call may pass h itself.
template <int D>
struct Support {
  double h, poly6, spiky, spiky_derivative, viscosity_laplacian;
  Support(double s)  // NOLINT(google-explicit-constructor): a support is its radius
      : h(s), poly6(constant::poly6<D>(s)), spiky(constant::spiky<D>(s)),
        spiky_derivative(constant::spiky_derivative<D>(s)), viscosity_laplacian(constant::viscosity_laplacian<D>(s)) {}
};

// The kernels taking a Support compute both sides and then choose (no branch), so that pair
// loops over batches of neighbours vectorise (sph/neighbour_batch.hpp); same values and bits.

/// The support h of a neighbour of a particle whose support is `si`: si itself when h is its
/// radius (the usual case), otherwise a new one (with a lookup).
template <int D>
inline Support<D> support_of(double h, const Support<D>& si) {
  return h == si.h ? si : Support<D>(h);
}

/// poly6: W = 315/(64π h⁹)(h²−r²)³ in 3-D, 4/(π h⁸)(h²−r²)³ in 2-D.
template <int D>
inline double poly6(double r, const Support<D>& s) {
  const double q = s.h * s.h - r * r;
  const double w = s.poly6 * q * q * q;
  return r >= s.h ? 0.0 : w;
}
template <int D>
inline double poly6(double r, double h) {
  if (r >= h) return 0.0;
  const double q = h * h - r * r;
  return constant::poly6<D>(h) * q * q * q;
}

/// poly6 gradient: −945/(32π h⁹)(h²−r²)² d in 3-D, −24/(π h⁸)(h²−r²)² d in 2-D.
template <int D>
inline Vec<D> poly6_gradient(const Vec<D>& d, double r, double h) {
  if (r >= h) return Vec<D>::Zero();
  const double q = h * h - r * r;
  const double c = remembered(h, [](double s) { return D == 3 ? -945.0 / (32.0 * pi * std::pow(s, 9)) : -24.0 / (pi * std::pow(s, 8)); });
  return (c * q * q) * d;
}

/// poly6 Laplacian: −945/(32π h⁹)(h²−r²)(3h²−7r²) in 3-D, −48/(π h⁸)(h²−r²)(h²−3r²) in 2-D.
template <int D>
inline double poly6_laplacian(double r, double h) {
  if (r >= h) return 0.0;
  const double q = h * h - r * r;
  if constexpr (D == 3) return remembered(h, [](double s) { return -945.0 / (32.0 * pi * std::pow(s, 9)); }) * q * (3.0 * h * h - 7.0 * r * r);
  else return remembered(h, [](double s) { return -48.0 / (pi * std::pow(s, 8)); }) * q * (h * h - 3.0 * r * r);
}

/// spiky: W = 15/(π h⁶)(h−r)³ in 3-D, 10/(π h⁵)(h−r)³ in 2-D.
template <int D>
inline double spiky(double r, const Support<D>& s) {
  const double q = s.h - r;
  const double w = s.spiky * q * q * q;
  return r >= s.h ? 0.0 : w;
}
template <int D>
inline double spiky(double r, double h) {
  if (r >= h) return 0.0;
  const double q = h - r;
  return constant::spiky<D>(h) * q * q * q;
}

/// spiky derivative dW/dr: −45/(π h⁶)(h−r)² in 3-D, −30/(π h⁵)(h−r)² in 2-D.
template <int D>
inline double spiky_derivative(double r, double h) {
  if (r >= h) return 0.0;
  const double q = h - r;
  return constant::spiky_derivative<D>(h) * q * q;
}

template <int D>
inline double spiky_derivative(double r, const Support<D>& s) {
  const double q = s.h - r;
  const double w = s.spiky_derivative * q * q;
  return r >= s.h ? 0.0 : w;
}

/// The factor W'(r)/r of the spiky gradient (below), 0 where the gradient is zero.
template <int D>
inline double spiky_gradient_factor(double r, const Support<D>& s) {
  const double w = spiky_derivative<D>(r, s) / (r > 0.0 ? r : 1.0);
  return r >= s.h || r <= 0.0 ? 0.0 : w;
}

/// spiky gradient W'(r) d/r (zero at r = 0, where the direction is undefined).
template <int D>
inline Vec<D> spiky_gradient(const Vec<D>& d, double r, const Support<D>& s) {
  if (r >= s.h || r <= 0.0) return Vec<D>::Zero();
  return (spiky_derivative<D>(r, s) / r) * d;
}
template <int D>
inline Vec<D> spiky_gradient(const Vec<D>& d, double r, double h) {
  if (r >= h || r <= 0.0) return Vec<D>::Zero();
  return (spiky_derivative<D>(r, h) / r) * d;
}

/// viscosity kernel W (3-D: 15/(2π h³)(−r³/(2h³) + r²/h² + h/(2r) − 1); 2-D: the kernel whose 2-D
/// Laplacian is exactly 40/(π h⁵)(h − r), docs/equations.md §1). Singular at r = 0; use it only through
/// its Laplacian.
template <int D>
inline double viscosity(double r, double h) {
  if (r >= h || r <= 0.0) return 0.0;
  if constexpr (D == 3)
    return 15.0 / (2.0 * pi * h * h * h) * (-r * r * r / (2.0 * h * h * h) + r * r / (h * h) + h / (2.0 * r) - 1.0);
  else
    return 40.0 / (pi * std::pow(h, 5)) *
           (h * h * h / 6.0 * std::log(h / r) + h * r * r / 4.0 - r * r * r / 9.0 - 5.0 * h * h * h / 36.0);
}

/// viscosity Laplacian: 45/(π h⁶)(h−r) in 3-D, 40/(π h⁵)(h−r) in 2-D (non-negative).
template <int D>
inline double viscosity_laplacian(double r, const Support<D>& s) {
  const double w = s.viscosity_laplacian * (s.h - r);
  return r >= s.h ? 0.0 : w;
}
template <int D>
inline double viscosity_laplacian(double r, double h) {
  if (r >= h) return 0.0;
  return constant::viscosity_laplacian<D>(h) * (h - r);
}

/// Which kernel the density summation (eq 6) uses. Müller 2003 uses poly6; its flat top lets
/// particles pair up under the stiff state equation that validation needs (the hydrostatic tank
/// at h = 3 dx does not stay at rest with it), so the default is the spiky kernel, whose peak keeps
/// particles apart. Both have the exact constants above.
enum class DensityKernel { Poly6, Spiky };

template <int D>
inline double density_kernel(DensityKernel k, double r, const Support<D>& s) {
  return k == DensityKernel::Spiky ? spiky<D>(r, s) : poly6<D>(r, s);
}
template <int D>
inline double density_kernel(DensityKernel k, double r, double h) {
  return k == DensityKernel::Spiky ? spiky<D>(r, h) : poly6<D>(r, h);
}

/// Shooting/gathering average of a kernel function over the two supports h_i and h_j
/// (Desbrun & Cani 1996 as used by Adams 2007): pair terms built from it are symmetric in i, j.
/// Equal supports (most pairs) take one evaluation: 0.5 (k + k) = k holds exactly in floating
/// point, so the result has the same bits as the two-evaluation form.
/// `kernel_at` takes a Support; i's is given, j's constants are looked up only when h_j differs.
template <int D, class F>
inline auto pair_average(F&& kernel_at, const Support<D>& si, double hj) {
  using T = decltype(kernel_at(si));
  if (si.h == hj) return T(kernel_at(si));
  return T(0.5 * (kernel_at(si) + kernel_at(Support<D>(hj))));
}

}  // namespace sc::kernel
