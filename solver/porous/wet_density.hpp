// Rest density and mass of a wet porous particle (Lenaerts et al. 2008 eq 11 and §4: "particles
// gain weight"; thesis §3.4: the absorbed fluid mass is taken into account in all computations).
#pragma once
#include "core/particle_set.hpp"

namespace sc {

/// Wet rest density [thesis eq. 31] (Lenaerts eq 11): ρ0_i = ρ0 + S_i φ_i ρ0^fluid, with ρ0 the dry
/// bulk rest density of the porous material. Correct as printed. Scope (docs/equations.md, eq 31): apply it
/// to porous (sand) particles only, never to water particles that take part in the exchange as
/// "porous" with φ = 1, S = 1, whose rest density it would double.
inline double wet_rest_density(double dry_rest_density, double saturation, double porosity, double fluid_density) {
  return dry_rest_density + saturation * porosity * fluid_density;
}

/// Water inside particle i [kg]: its absorbed water m_p and its emission store.
template <int D>
double held_water(const ParticleSet<D>& ps, std::size_t i) {
  return ps.absorbed[i] + ps.emit_store[i];
}

/// True for a particle whose held water is part of its mass m (so of its weight, inertia, density
/// sum and rigid cluster): moving porous sand. A fixed porous bed does not move, and its mass is
/// that of its wall model; water is never porous.
template <int D>
bool carries_held_water(const ParticleSet<D>& ps, std::size_t i) {
  return ps.phase_of(i) == Phase::Sand && ps.porosity[i] > 0.0;
}

/// Rest density of eq 31 of a particle carrying held water (carries_held_water) whose mass m is
/// its dry mass plus held_water, at rest volume V0 (m/ρ0, which held water does not change):
/// the dry bulk density (m − held)/V0 and the saturation of the held water in the pores φ0 V0 of
/// the undeformed skeleton. The store counts: it is water in the particle until it leaves. Then
/// m/ρ0 = V0 whatever the particle holds, so its rest spacing and the volume its neighbours count
/// it with (sph/density.hpp neighbour_mass) stay those of the grain. [thesis eq. 31]
template <int D>
void set_wet_rest_density(ParticleSet<D>& ps, std::size_t i, double rest_volume, double porosity0,
                          double fluid_density) {
  const double held = held_water(ps, i);
  ps.rho0[i] = wet_rest_density((ps.m[i] - held) / rest_volume, held / (fluid_density * porosity0 * rest_volume),
                                porosity0, fluid_density);
}

/// Makes the held water of a dry-massed particle (mass and rest density of the dry grain, as the
/// scene builds it) part of it: m ← m + held_water, ρ0 of eq 31.
template <int D>
void take_in_held_water(ParticleSet<D>& ps, std::size_t i, double porosity0, double fluid_density) {
  const double rest_volume = ps.m[i] / ps.rho0[i];
  ps.m[i] += held_water(ps, i);
  set_wet_rest_density(ps, i, rest_volume, porosity0, fluid_density);
}

}  // namespace sc
