// The vertical cut in cohesive-frictional soil: Mohr-Coulomb's unconfined strength and Rankine's
// critical height (docs/references.md §13, docs/equations.md §9).
#pragma once
#include <cmath>
#include <numbers>

namespace sc::analytic {

/// The unconfined compressive strength of a Mohr-Coulomb material of cohesion c [Pa] and friction
/// angle φ [deg]: with the lateral stress zero, |σ1 − σ3| ≤ 2c cos φ − (σ1 + σ3) sin φ (tension
/// positive) holds up to q_u = 2c cos φ/(1 − sin φ) = 2c tan(45° + φ/2). [Mohr-Coulomb: unconfined strength]
inline double unconfined_strength(double cohesion, double friction_angle_deg) {
  return 2.0 * cohesion * std::tan((45.0 + friction_angle_deg / 2.0) * std::numbers::pi / 180.0);
}

/// Rankine's critical height of a vertical cut, H_c = (4c/(ρ_b g)) tan(45° + φ/2) = 2 q_u/(ρ_b g)
/// (ρ_b the bulk density, g gravity): in the active state the lateral stress ρ_b g z K_a − 2c √K_a
/// (K_a = tan²(45° − φ/2)) is tension down to z0 = H_c/2 and pressure below, and the thrust on the
/// face, its integral over the height, vanishes at H = 2 z0. [Rankine: critical height]
inline double rankine_critical_height(double cohesion, double friction_angle_deg, double bulk_density, double g) {
  return 2.0 * unconfined_strength(cohesion, friction_angle_deg) / (bulk_density * g);
}

}  // namespace sc::analytic
