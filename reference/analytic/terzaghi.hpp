// Terzaghi's one-dimensional consolidation (docs/references.md §13) [exact for the linear theory].
#pragma once
#include <cmath>
#include <numbers>

namespace sc::analytic {

/// The degree of consolidation of a layer draining at one face under a load applied at t = 0 (the
/// pore water carrying it all at first), at the time factor T_v = c_v t / H² (H the drainage length,
/// c_v = K E_oed / (ρ_w g) the coefficient of consolidation):
///   U(T_v) = 1 − Σ_{m≥0} (2/M²) exp(−M² T_v),  M = π (2m + 1)/2,
/// the settlement over its final value, and 1 − the mean excess pore pressure over the load.
/// The series is summed until a term falls below 1e-15 (T_v > 0; U(0) = 0).
/// [Terzaghi 1943: consolidation]
inline double terzaghi_consolidation_degree(double Tv) {
  if (Tv <= 0.0) return 0.0;
  double sum = 0.0;
  for (int m = 0;; ++m) {
    const double M = std::numbers::pi * (2.0 * m + 1.0) / 2.0;
    const double term = 2.0 / (M * M) * std::exp(-M * M * Tv);
    sum += term;
    if (term < 1e-15) break;
  }
  return 1.0 - sum;
}

}  // namespace sc::analytic
