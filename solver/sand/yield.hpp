// Mohr-Coulomb (Drucker-Prager-like) yield test of Zhu & Bridson 2005 with the rigid stress.
#pragma once
#include <cmath>
#include <numbers>

#include "core/types.hpp"
#include "sand/sand_params.hpp"

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

/// Length L of the rigid stress [thesis eq. 12a] of a particle with kernel support `support` and
/// spacing `spacing` (s_i = V_i^(1/D)): the spacing (RigidStressLength::Spacing, default) or, as
/// printed, the support (RigidStressLength::Support, case key sand.rigid_stress_length = "support").
inline double rigid_stress_length(RigidStressLength form, double support, double spacing) {
  return form == RigidStressLength::Support ? support : spacing;
}

/// Strength factor k of the yield test: the factor on sin φ σ_m in eq 10 for each yield surface.
/// The flowing stress σ_f of eq 8 (traceless D) has √3 σ̄_f = (3/√2) sin φ p (docs/equations.md,
/// eq 8, erratum 8d), so with k = 1 (eq 10 as printed) the stress of yielding sand lies 3/√2 ≈ 2.12 times outside the
/// yield surface. Then a slope stands statically only while sin θ < sin φ/√3 (θ < 16.8° for
/// φ = 30°, the Mohr circle of a slope with σ̄/σ_m ≥ sin θ), although flowing sand stops on slopes up
/// to tan θ = √(3/2) sin φ (31.5°): between the two the flanks of a pile never turn rigid and keep
/// creeping (the angle_of_repose case). k = 3/√2 puts eq 10's yield surface on the
/// flowing stress of eq 8 (sand yields exactly when friction can no longer supply the stress that
/// would stop it, the consistency of a rigid-plastic model), so the repose angle is the angle where
/// flow stops, tan θ_r = √(3/2) sin φ (within 1.7° of φ for φ in [20°, 35°]).
inline double yield_strength_factor(YieldSurface surface) {
  return surface == YieldSurface::FlowConsistent ? 3.0 / std::numbers::sqrt2 : 1.0;
}

/// Yield test [thesis eq. 10]: the material does not yield (is rigid) while
///   √3 σ̄ < k sin φ σ_m + c,
/// evaluated for σ = p I + σ_rigid (compression positive), with the strength factor k of
/// yield_strength_factor (k = 1: eq 10 as printed by the thesis and Zhu & Bridson). Interpretation
/// (docs/equations.md, eq 10): the mean stress must include the pressure p; σ_rigid alone is nearly traceless,
/// so without p nothing would ever be rigid without cohesion (the bug of the public Taichi code).
/// c ≥ 0 is the cohesion [Pa].
template <int D>
inline bool is_rigid(const Mat<D>& rigid_stress_tensor, double pressure, double sin_phi, double cohesion,
                     double strength = 1.0) {
  const Mat<D> sigma = pressure * Mat<D>::Identity() + rigid_stress_tensor;
  return std::sqrt(3.0) * shear_stress<D>(sigma) < strength * sin_phi * mean_stress<D>(sigma) + cohesion;
}

}  // namespace sc
