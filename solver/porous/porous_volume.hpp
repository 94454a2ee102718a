// The volume of a porous particle: the one convention of porous flow (saturation, capacity, pair
// flows, the flux calibration λ, emission), for fixed and moving skeletons alike.
#pragma once
#include <cmath>

#include "core/particle_set.hpp"
#include "porous/porous_params.hpp"

namespace sc {

/// Volume V_i of porous particle i in [thesis eq. 21] (S = m_p/(ρ^f φ V)) and in the pair flows of
/// [thesis eq. 28]: m_i/ρ0_i, fixed or moving: the dry skeleton's mass over its rest density, and
/// for moving sand, whose mass and rest density include its held water (porous/wet_density.hpp,
/// eq 31), the same rest volume, which held water does not change.
/// Why this measure: the masses are calibrated so that a lattice reads its rest density (eq 6),
/// m = ρ0 / Σ_k W(|k| dx, h), so m/ρ0 is not the site's dx^D but the particle's SPH volume (less than
/// dx^D: the self term makes the lattice sum exceed the kernel's integral), and a water particle
/// fills its site with m_w = ρ^f m/ρ0 of water by the same rule. With V = m/ρ0 a saturated site holds φ m_w, so the water volume a
/// pond loses (a full water particle per site) is the pore volume its bed fills, and a fixed and a
/// moving bed hold and pass the same water (tests porous/a_saturated_bed_holds_the_same_water_fixed_or_moving,
/// porous/a_pond_loses_the_water_volume_its_bed_fills). Not m/ρ: the summation density of sand
/// is short at every free surface and where water borders it, which would swell V there; the
/// skeleton's compression enters through the porosity of [thesis eq. 24].
template <int D>
double porous_volume(const ParticleSet<D>& ps, std::size_t i) {
  return ps.m[i] / ps.rho0[i];
}

/// V0 = m_w/ρ^f: the porous_volume of every particle of the case's lattice at sampling level 0
/// (sand and water masses are calibrated on the same lattice and kernel), on which the flux
/// length λ is calibrated (derive_porous).
inline double lattice_volume(const PorousParams& p) { return p.water_mass / p.fluid_density; }

/// Spacing of porous particle i: the edge of the lattice site it fills, dx (V_i/V0)^(1/D), i.e. dx
/// for a particle of the case's sampling, fixed or moving. The length of the contact with water,
/// of the emission target and of the half-space flow into air (porous_flow.cpp), which the
/// calibration of λ on sites of dx^D makes the flux per site face.
template <int D>
double porous_spacing(const ParticleSet<D>& ps, std::size_t i, const PorousParams& p) {
  return particle_size<D>(porous_volume(ps, i) / lattice_volume(p) * std::pow(p.spacing, D));
}

}  // namespace sc
