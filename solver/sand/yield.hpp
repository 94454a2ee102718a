// Mohr-Coulomb (Drucker-Prager-like) yield test of Zhu & Bridson 2005 with the rigid stress.
#pragma once
#include <cmath>

#include "core/types.hpp"

namespace sc {

/// Mean stress σ_m = tr(σ)/D (compression positive). The thesis writes tr(σ)/3 for 3-D; in 2-D
/// (plane strain) the mean over the two in-plane directions is used.
template <int D>
inline double mean_stress(const Mat<D>& sigma) {
  return sigma.trace() / D;
}

/// Shear stress [thesis eq. 11]: σ̄ = |σ − σ_m δ|_F / √2 (Frobenius norm of the deviator; δ is the
/// identity). Correct as printed.
template <int D>
inline double shear_stress(const Mat<D>& sigma) {
  return (sigma - mean_stress<D>(sigma) * Mat<D>::Identity()).norm() / std::sqrt(2.0);
}

/// Rigid stress [thesis eq. 12a]: the stress that would stop all relative motion within one step,
///   σ_rigid = −ρ D L² / Δt   [Pa, compression positive],
/// with D the strain rate [1/s] and L the length of Zhu & Bridson's grid cell. Erratum 12a: the
/// thesis uses the kernel support h (overestimating σ_rigid by (h/Δx)² ≈ 4-9, so sand yields too
/// readily); the particle analogue of Δx is the particle spacing s_i = V_i^(1/D) (the default; the
/// thesis' h is kept as the switch RigidStressLength::Support). With the thesis' dimensionless D
/// (from v Δt, eq 9) the units would be Pa·s; with the strain rate they are Pa.
template <int D>
inline Mat<D> rigid_stress(const Mat<D>& strain_rate, double density, double length, double dt) {
  return (-density * length * length / dt) * strain_rate;
}

/// Yield test [thesis eq. 10]: the material does not yield (is rigid) while
///   √3 σ̄ < sin φ σ_m + c,
/// evaluated for σ = p I + σ_rigid (compression positive). Interpretation (EQUATIONS.md 10): the mean
/// stress must include the pressure p; σ_rigid alone is nearly traceless, so without p nothing would
/// ever be rigid without cohesion (the bug of the public Taichi code). c ≥ 0 is the cohesion [Pa].
template <int D>
inline bool is_rigid(const Mat<D>& rigid_stress_tensor, double pressure, double sin_phi, double cohesion) {
  const Mat<D> sigma = pressure * Mat<D>::Identity() + rigid_stress_tensor;
  return std::sqrt(3.0) * shear_stress<D>(sigma) < sin_phi * mean_stress<D>(sigma) + cohesion;
}

}  // namespace sc
