// Hydrostatic pressure in a resting column (docs/references.md §1) [exact].
#pragma once

namespace sc::analytic {

/// p(z) = ρ0 g (H − z) for a column of height H (surface at z = H, floor at z = 0); zero above H.
inline double hydrostatic_pressure(double rho0, double g, double H, double z) {
  return z >= H ? 0.0 : rho0 * g * (H - z);
}

}  // namespace sc::analytic
