// Forces on DEM grains and their time integration (Rungjiratananon et al. 2008, seed 003): contacts
// between grains and with the tank's walls, liquid bridges between wet grains, gravity. Each grain
// gathers its own contacts over the cell grid (no scatter, no atomics), so 1 and 2 threads give
// bitwise the same forces.
#pragma once
#include <span>

#include "dem/cell_grid.hpp"
#include "dem/contact_laws.hpp"
#include "dem/grains.hpp"

namespace sc::dem {

/// Largest centre distance at which two grains interact (contact or bridge) [m]: the cell size
/// of the contact grid.
template <int D>
double interaction_range(const Grains<D>& g, const Params& p);

/// Bins the grains for the contact gather (cell size interaction_range).
template <int D>
void bin_grains(const Grains<D>& g, const Params& p, CellGrid<D>& grid);

/// Force and torque on grain i from grain j (contact and bridge) over a step Δt; zero when apart.
/// `spring` holds i's springs of the contact (relaxed for a new one) and is advanced by Δt.
template <int D>
ContactForce<D> pair_force(const Grains<D>& g, std::size_t i, std::size_t j, const Params& p, double dt,
                           Spring<D>& spring);

/// Force and torque on grain i from a wall plane (contact with Params::wall_friction on a rough wall).
template <int D>
ContactForce<D> wall_force(const Grains<D>& g, std::size_t i, const Plane<D>& wall, const Params& p, double dt,
                           Spring<D>& spring);

/// Sets force and torque of every grain over a step Δt: gravity, pair contacts and bridges, walls;
/// each grain's contact springs advance and only those of contacts that still touch are kept.
template <int D>
void grain_forces(Grains<D>& g, const CellGrid<D>& grid, const Params& p, const Vec<D>& gravity,
                  std::span<const Plane<D>> walls, double dt);

/// Symplectic Euler: v += Δt F/m, ω += Δt T/I, then x += Δt v.
template <int D>
void integrate(Grains<D>& g, const Params& p, double dt);

/// One dry or wet DEM step without water: bin, forces, integrate.
template <int D>
void step(Grains<D>& g, CellGrid<D>& grid, const Params& p, const Vec<D>& gravity, std::span<const Plane<D>> walls,
          double dt);

}  // namespace sc::dem
