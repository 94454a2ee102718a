// Capillary fringe above a free water table (docs/references.md §5) [exact for the model's potential].
#pragma once
#include <algorithm>
#include <cmath>

namespace sc::analytic {

/// Fringe height z_max = k^c/(ρ g): above it the capillary potential (thesis eq. 23) cannot lift water.
inline double fringe_height(double kc, double rho, double g) { return kc / (rho * g); }

/// Equilibrium saturation at height z above the table, where ∇P^c balances ρ g (pore velocity of
/// eq 27 zero without pore pressure): S(z) = 1 − (ρ g z / k^c)^(1/α) for 0 ≤ z ≤ z_max, 0 above.
inline double equilibrium_saturation(double z, double kc, double rho, double g, double alpha) {
  if (z <= 0.0) return 1.0;
  return std::max(0.0, 1.0 - std::pow(std::min(1.0, rho * g * z / kc), 1.0 / alpha));
}

/// Water held above the table per unit area [m]: ∫ φ S dz = φ k^c / (ρ g (α + 1)).
inline double held_water(double kc, double rho, double g, double alpha, double porosity) {
  return porosity * kc / (rho * g * (alpha + 1.0));
}

/// Height where the equilibrium saturation equals S: z = z_max (1 − S)^α.
inline double height_at_saturation(double S, double kc, double rho, double g, double alpha) {
  return fringe_height(kc, rho, g) * std::pow(1.0 - S, alpha);
}

}  // namespace sc::analytic
