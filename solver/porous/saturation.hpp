// Saturation and porosity of porous particles (Lenaerts et al. 2008 eqs 2 and 5).
#pragma once
#include <algorithm>

namespace sc {

/// Saturation [thesis eq. 21] (Lenaerts eq 2): S_i = m_pi / (ρ^fluid φ_i V_i), clamped to [0, 1].
/// Correct as printed. m_p is the absorbed water mass, φ_i V_i the pore volume of the particle.
inline double saturation(double absorbed_mass, double fluid_density, double porosity, double volume) {
  const double capacity = fluid_density * porosity * volume;
  return capacity > 0.0 ? std::clamp(absorbed_mass / capacity, 0.0, 1.0) : 0.0;
}

/// Porosity [thesis eq. 24] (Lenaerts eq 5): φ_i = φ0 ρ0^s / ρ_i^s, clamped to φ ≤ 1. Correct as
/// printed: compressing the skeleton (ρ^s > ρ0^s) lowers the pore space.
inline double porosity(double porosity0, double rest_density, double density) {
  return std::min(1.0, porosity0 * rest_density / density);
}

}  // namespace sc
