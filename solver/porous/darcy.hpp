// Darcy's law and the pore velocity (Darcy 1856; Lenaerts et al. 2008 eq 7).
#pragma once
#include "core/types.hpp"

namespace sc {

/// Darcy flux [thesis eq. 26]: q = −(k/μ)(∇P − ρ^f g) [m/s], with k the intrinsic permeability
/// [m^2], μ the dynamic viscosity of the pore water and ρ^f its density. Correct as printed
/// (hydrostatic ∇P = ρ^f g gives q = 0). The hydraulic conductivity is K_h = k ρ^f |g| / μ.
template <int D>
inline Vec<D> darcy_flux(double permeability, double viscosity, const Vec<D>& grad_p, double fluid_density,
                         const Vec<D>& gravity) {
  return (-permeability / viscosity) * (grad_p - fluid_density * gravity);
}

/// Pore velocity [thesis eq. 27] (Lenaerts eq 7): v_p = −k/(φμ)(∇P^p − ∇P^c − ρ^f g), the Darcy
/// flux of eq 26 divided by the porosity, with the pore-water pressure P^p − P^c (pore pressure
/// minus capillary suction). Correct as printed once eq 25 has Lenaerts' ratio: with capillarity
/// alone v_p points up ∇P^c, towards drier particles.
template <int D>
inline Vec<D> pore_velocity(double permeability, double viscosity, double porosity, const Vec<D>& grad_pore,
                            const Vec<D>& grad_capillary, double fluid_density, const Vec<D>& gravity) {
  return darcy_flux<D>(permeability, viscosity, Vec<D>(grad_pore - grad_capillary), fluid_density, gravity) / porosity;
}

}  // namespace sc
