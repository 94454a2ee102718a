// Frictional stress of flowing sand (Zhu & Bridson 2005).
#pragma once
#include <algorithm>
#include <cmath>

#include "core/types.hpp"

namespace sc {

/// Frictional stress [thesis eq. 8], compression positive (geomechanics convention, §0), in Pa:
///   σ_f = −sin φ · p · D / (√(1/3) |D|_F),
/// with p ≥ 0 the SPH pressure (negative p is clamped to 0: no friction in tension) and σ_f = 0 when
/// |D|_F < `tiny`. Errata of eq 8: (a) the thesis omits the pressure p, leaving a dimensionless
/// "stress"; (b) it writes √(|D|_F/3) where Zhu & Bridson have √(1/3)·|D|_F (the printed form is not
/// even homogeneous in D). μ_f = sin φ. Hence |σ_f|_F = √3 sin φ p for every D ≠ 0, independent of
/// the magnitude of D (rate independent). ZB's constant is kept for fidelity although √3 σ̄ of this
/// stress is (3/√2) sin φ p, not the yield value sin φ p of eq 10 (docs/equations.md, eq 8, erratum 8d).
template <int D>
inline Mat<D> frictional_stress(const Mat<D>& strain_rate, double pressure, double sin_phi, double tiny = 1e-12) {
  const double norm = strain_rate.norm();  // Frobenius
  const double p = std::max(0.0, pressure);
  if (norm < tiny || p == 0.0) return Mat<D>::Zero();
  return (-sin_phi * p / (std::sqrt(1.0 / 3.0) * norm)) * strain_rate;
}

}  // namespace sc
