// Coupling of DEM grains with the project's SPH water (core/particle_set.hpp, water/), after
// Rungjiratananon et al. 2008 (seed 003). The water keeps its own SPH density, pressure and
// viscosity (computed by the SPH step); this file adds only the water-grain terms, built on the
// project's pair forces (water/pressure_force.hpp, water/viscosity_force.hpp):
// - pressure and viscous forces between a water particle and a grain, equal and opposite;
// - absorption: a water particle next to a dry or moist grain is taken up, its mass becoming water
//   held by the grain and its momentum joining the grain's.
// Order within a coupled step: the grains and the SPH water each advance over the step with their
// own forces, then exchange_with_water (the coupling forces as an impulse on both, absorption,
// wetness propagation). DemMethod (solver/dem/dem_method.hpp) runs it behind the method seam.
#pragma once
#include "core/particle_set.hpp"
#include "neighbours/cell_grid.hpp"
#include "dem/grains.hpp"
#include "dem/wetness.hpp"

namespace sc::dem {

/// Cell grids of grains and water for the coupling gathers (cell: the coupling support, or the
/// absorption reach if larger).
template <int D>
struct CouplingGrids {
  CellGrid<D> grains, water;
};

template <int D>
void bin_coupling(const Grains<D>& g, const ParticleSet<D>& water, const Params& p, CouplingGrids<D>& grids);

/// Force on water particle i from grain k [Rungjiratananon 2008: water-grain pressure and viscosity,
/// fixed]:
///   F^p = −(V_i V_g/4)(p_i + p_g) ∇W_spiky(x_i − x_g, h),
///   F^v = μ (V_i V_g/2) ∇²W_visc(|x_i − x_g|, h) (v_g − v_i)
/// (the seed's viscous term lacks the velocity difference). The grain receives −F.
template <int D>
Vec<D> water_grain_force(const ParticleSet<D>& water, std::size_t i, const Grains<D>& g, std::size_t k,
                         const Params& p);

/// Adds the water-grain forces to water.force (water particles) and g.force (grains): each side
/// gathers the same pair terms, so the total is zero to round-off.
template <int D>
void coupling_forces(Grains<D>& g, ParticleSet<D>& water, const CouplingGrids<D>& grids, const Params& p);

/// Absorbs water particles within absorb_distance of the surface of a grain that is not over-wet
/// (the nearest such grain, lower index on ties) [Rungjiratananon 2008: absorption, bounded]: the
/// grain takes the particle's mass up to its capacity (w <= 1, the paper's w_max = 1), in water
/// index order; the mass taken joins the grain's held water and carries the particle's velocity
/// into the grain's momentum (total mass, water and momentum conserved). A particle taken whole is
/// removed from `water` (compact), one taken in part keeps the rest of its mass and its velocity.
/// Returns how many were removed.
template <int D>
std::size_t absorb_water(Grains<D>& g, ParticleSet<D>& water, const CouplingGrids<D>& grids, const Params& p);

/// Scratch of exchange_with_water: its cell grids.
template <int D>
struct ExchangeGrids {
  CouplingGrids<D> coupling;
  CellGrid<D> grains;
};

/// The exchange of one coupled step of size dt, after the grains and the water have each advanced
/// with their own forces [Rungjiratananon 2008: water-grain pressure and viscosity, absorption,
/// wetness propagation]: the water-grain forces of the positions reached, as an impulse dt F on
/// both sides (v += dt F/m: equal and opposite, momentum conserved to round-off), then
/// absorb_water and propagate_wetness. Overwrites g.force and water.force.
template <int D>
void exchange_with_water(Grains<D>& g, ParticleSet<D>& water, const Params& p, double dt, ExchangeGrids<D>& grids);

}  // namespace sc::dem
