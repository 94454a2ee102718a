// Rest density of a wet porous particle (Lenaerts et al. 2008 eq 11).
#pragma once

namespace sc {

/// Wet rest density [thesis eq. 31] (Lenaerts eq 11): ρ0_i = ρ0 + S_i φ_i ρ0^fluid, with ρ0 the dry
/// bulk rest density of the porous material. Correct as printed. Scope (docs/equations.md, eq 31): apply it
/// to porous (sand) particles only, never to water particles that take part in the exchange as
/// "porous" with φ = 1, S = 1, whose rest density it would double.
inline double wet_rest_density(double dry_rest_density, double saturation, double porosity, double fluid_density) {
  return dry_rest_density + saturation * porosity * fluid_density;
}

}  // namespace sc
