// Porous flow in a case: reading the "porous" section, the initial state of porous particles,
// and the quantities derived from the case spacing.
#pragma once
#include "core/particle_set.hpp"
#include "io/json_reader.hpp"
#include "porous/porous_params.hpp"

namespace sc {

/// Reads the "porous" section (keys in cases/README.md). Porosity must lie in (0, 1), α in (0, 1],
/// β > 0; the pore water is the case's water (ρ^fluid = water.rest_density).
PorousParams read_porous(JsonObject o, double water_density);

/// Fills the derived members of `p` for a case of dimension D at spacing dx with support h and
/// full-size water particles of mass `water_mass`; λ is calibrated on the volume of the lattice's
/// particles, lattice_volume (porous/porous_volume.hpp).
template <int D>
void derive_porous(PorousParams& p, double dx, double h, double water_mass,
                   kernel::DensityKernel density_kernel = kernel::DensityKernel::Spiky);

/// Gives every particle that is not water (and exists now: call before adding tank walls) the
/// porosity φ0 and absorbed water S0 ρ^f φ0 V, V its porous_volume (fixed or moving alike); moving
/// sand takes that water into its mass and rest density (take_in_held_water, eq 31).
template <int D>
void init_porous(ParticleSet<D>& ps, const PorousParams& p);

}  // namespace sc
