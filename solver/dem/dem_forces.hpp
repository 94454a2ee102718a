// Forces on DEM grains and their time integration (Rungjiratananon et al. 2008, seed 003): contacts
// between grains and with the tank's walls, liquid bridges between wet grains, gravity. Each listed
// pair of grains is evaluated once, by its lower grain, into a slot of its own; then each grain
// gathers its pairs' slots in its list's order and its walls (no scatter, no atomics), so 1 and 2
// threads give bitwise the same forces.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "neighbours/cell_grid.hpp"
#include "dem/contact_laws.hpp"
#include "dem/grains.hpp"
#include "dem/neighbour_list.hpp"

namespace sc::dem {

/// Largest centre distance at which two grains interact (contact or bridge) [m]: the cell size
/// of the contact grid.
template <int D>
double interaction_range(const Grains<D>& g, const Params& p);

/// What the contact step keeps from step to step: the neighbour list and the grains that may reach
/// a wall while it stands, and per listed pair (numbered by the list) its contact of the step,
/// evaluated once for both grains. Sized with the list, so a step allocates nothing once the list
/// has stopped growing.
template <int D>
struct Contacts {
  NeighbourList<D> near;
  std::vector<std::uint8_t> near_wall;  ///< per grain: within its radius plus the skin of a wall at the build
  std::vector<ContactForce<D>, Eigen::aligned_allocator<ContactForce<D>>> pair;  ///< from the lower grain i's side
  std::vector<std::uint8_t> acts;  ///< whether the pair may interact this step (pair is set only then)
};

/// Bins the grains by interaction_range (the wetness gather, solver/dem/wetness.hpp).
template <int D>
void bin_grains(const Grains<D>& g, const Params& p, CellGrid<D>& grid);

/// Builds the contact step's neighbour list again when it is stale (a grain moved more than half
/// its skin, a tenth of interaction_range, or the range grew), and with it which grains may reach a
/// wall before the next build: those within their radius plus the whole skin of it (twice the
/// distance a grain moves meanwhile, so no contact is missed). The others skip the walls, so `walls`
/// must be those of the steps that use the list.
template <int D>
void update_neighbours(const Grains<D>& g, const Params& p, std::span<const Plane<D>> walls, Contacts<D>& contacts);

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
/// the contacts' springs advance and only those of contacts that still touch are kept. Each pair in
/// `contacts.near` is evaluated once (for its lower grain, with the springs that grain keeps of it);
/// each grain's sums are, bit for bit, those of evaluating every one of its contacts from its side.
template <int D>
void grain_forces(Grains<D>& g, Contacts<D>& contacts, const Params& p, const Vec<D>& gravity,
                  std::span<const Plane<D>> walls, double dt);

/// Symplectic Euler: v += Δt F/m, ω += Δt T/I, then x += Δt v.
template <int D>
void integrate(Grains<D>& g, const Params& p, double dt);

/// One dry or wet DEM step without water: neighbours, forces, integrate.
template <int D>
void step(Grains<D>& g, Contacts<D>& contacts, const Params& p, const Vec<D>& gravity,
          std::span<const Plane<D>> walls, double dt);

}  // namespace sc::dem
