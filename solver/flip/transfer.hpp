// Particle-grid transfers of the PIC/FLIP solver (Zhu & Bridson 2005). Every sum runs in a fixed
// particle order (the bin order), each grid value written by one thread: the same bits with any
// number of threads.
#pragma once
#include <span>
#include <vector>

#include "flip/mac_grid.hpp"

namespace sc::flip {

/// Particles sorted by the cell containing them (a stable counting sort: within a cell, by index).
template <int D>
struct ParticleBins {
  std::vector<std::size_t> start;  ///< particles of cell c are order[start[c] .. start[c+1])
  std::vector<std::size_t> order;

  void build(const MacGrid<D>& grid, std::span<const Vec<D>> x);
  std::span<const std::size_t> in(std::size_t cell) const {
    return {order.data() + start[cell], order.data() + start[cell + 1]};
  }
};

/// Particle-to-grid transfer [Zhu-Bridson 2005: Transferring to the Grid]: each face value is the
/// weighted average of the particle velocities (component a) with the trilinear weight
/// w = Π_d max(0, 1 − |x_p,d − x_f,d|/Δx) (support twice the cell width), weighted also by the
/// particle mass: u_f = Σ w m v / Σ w m. `weight` receives Σ w m [kg] per face (0: no particle near).
template <int D>
void particles_to_grid(const MacGrid<D>& grid, const ParticleBins<D>& bins, std::span<const Vec<D>> x,
                       std::span<const Vec<D>> v, std::span<const double> m, FaceField<D>& u, FaceField<D>& weight);

/// Cell labels [Zhu-Bridson 2005: Fluid Simulation Revisited] ("some sort of indicator where the
/// fluid is"): air without particles, else sand or water by the larger particle mass in the cell.
/// `phase[p]` is particle p's Phase as an integer.
template <int D>
std::vector<Cell> label_cells(const MacGrid<D>& grid, const ParticleBins<D>& bins, std::span<const double> m,
                              std::span<const std::uint8_t> phase);

/// Distance from each air cell centre to the particles' surface [Zhu-Bridson 2005: Surface
/// Reconstruction]: φ(x) = |x − x̄| − r̄, with x̄ and r̄ the means of the particle positions and radii
/// (r_i half the particle's spacing (m/ρ)^(1/D)) weighted by k(|x − x_i|/R) = (1 − |x − x_i|²/R²)³,
/// R twice the mean particle spacing; clamped to [0, Δx] (Δx with no particle within R, in fluid
/// cells and in air cells with no fluid face neighbour, where it is never read). It places the
/// free surface p = 0 between an air cell and its fluid neighbour (pressure.hpp surface_fraction).
template <int D>
std::vector<double> air_distance(const MacGrid<D>& grid, const ParticleBins<D>& bins, std::span<const Vec<D>> x,
                                 std::span<const double> radius, const std::vector<Cell>& label);

/// Grid-to-particle update [Zhu-Bridson 2005: Updating Particle Velocities] of a particle of
/// velocity v, given the new and the old grid velocity interpolated at the particle (pic, old): PIC
/// takes pic, FLIP adds the change pic − old to the particle's velocity; v ← (1 − r) v_PIC + r v_FLIP
/// with the FLIP ratio r (near 1 for water). Sand does not pass here: it is PIC ("for viscous flow
/// such as sand"), its velocity the grid's (FlipSolver::update_particles).
template <int D>
Vec<D> grid_to_particle(const Vec<D>& pic, const Vec<D>& old, const Vec<D>& v, double flip_ratio);

/// Midpoint (RK2) advection through the grid velocity u [Zhu-Bridson 2005: Moving Particles] from x,
/// where u's velocity is u_x, then a particle that ends in a wall is moved just inside the tank (a
/// tenth of Δx from the wall).
template <int D>
Vec<D> advect_rk2(const MacGrid<D>& grid, const FaceField<D>& u, const Vec<D>& x, const Vec<D>& u_x, double dt);

}  // namespace sc::flip
