// Pore pressure of a porous particle (Lenaerts et al. 2008 eq 6).
#pragma once
#include <cmath>

namespace sc {

/// Pore pressure [thesis eq. 25] (Lenaerts eq 6): P^p = k^p S ((ρ^s/ρ0^s)^γ − 1).
/// Erratum: the thesis prints the inverted ratio (ρ0^s/ρ^s)^γ, with which a squeezed skeleton
/// sucks water in instead of pushing it out. `thesis_ratio` = true selects the printed form
/// (documented switch, case key porous.thesis_pore_pressure_ratio).
inline double pore_pressure(double kp, double saturation, double density, double rest_density, double gamma,
                            bool thesis_ratio = false) {
  const double ratio = thesis_ratio ? rest_density / density : density / rest_density;
  return kp * saturation * (std::pow(ratio, gamma) - 1.0);
}

}  // namespace sc
