// Pore-water pressure in a rigid saturated skeleton (ours [I]; Darcy 1856, incompressible pore water).
#pragma once
#include <cstdint>
#include <vector>

#include "core/particle_set.hpp"
#include "neighbours/neighbour_grid.hpp"
#include "parallel/decomposition.hpp"

namespace sc {

/// Role of a particle in the pore-pressure solve.
enum class PressureRole : std::uint8_t {
  None,       ///< takes no part (water, non-porous walls): a missing neighbour is a no-flow side
  Unknown,    ///< saturated rigid porous particle: P is solved for
  Prescribed  ///< porous particle whose P is given (pond contact, seepage face, unsaturated, moving sand)
};

/// Solves for P at the particles with role Unknown, the others with role Prescribed holding their
/// value in `P` (a Dirichlet condition), particles with role None being absent (no flow across).
/// Why: in a rigid saturated skeleton with homogeneous permeability the pore water is
/// incompressible, so the Darcy flux of [thesis eq. 27] (eq 26 / φ), v_p ∝ −∇Φ with the
/// piezometric pore-water pressure Φ = P − P^c − ρ^f g·x (P^c = `suction`, the capillary potential
/// of [thesis eq. 23]), is divergence-free: ∇²Φ = 0 (P − P^c is linear along a permeameter), and
/// an absent neighbour is a no-flow side, ∂Φ/∂n = 0 (at a floor: ∂P/∂z = −ρ^f g, hydrostatic).
/// P^c enters because the flux answers to P^p − P^c, not to P^p: at a wetting front the
/// unsaturated particles hold P = 0, i.e. pore water at −P^c, and that suction drives the whole
/// wet zone (the Green-Ampt suction head). Solving for P alone stopped the suction at the front
/// and left the wet zone's own P^c (~0.55 k^c at S ≈ 0.997 with α = 0.1) out of the balance.
/// Discretisation: the SPH Laplacian of Brookshaw (1985), Σ_j w_ij (Φ_j − Φ_i) = 0 with the
/// symmetric weights w_ij = |∇W_spiky(r_ij, h̄_ij)| / r_ij (equal volumes) (compact: no odd-even mode), solved
/// by conjugate gradients warm-started from `P` (core/conjugate_gradient.hpp: serial, its sums in
/// one order for every instruction set, so bitwise reproducible across threads and builds). A cluster of
/// unknowns with no prescribed neighbour has no defined pressure: a relative regularisation of
/// 1e-9 on the diagonal sets it to 0.
/// Hydrostatic pressure of every water particle from the water column above it, ours [I]:
/// P_j = ρ^f |g| s (Σ_{k above j} m_k + m_j/2) / m0, summing the water particles k in the same
/// vertical column of width s (the spacing; cells of the horizontal axes, gravity along the last
/// axis); a full particle (mass m0, the lattice mass that makes the SPH density ρ^f) is one
/// spacing of water height, a shrunken one a fraction of it. A gap of more than 1.5 spacings
/// with no water beside it either (in the columns next to this one) ends a column: water dripping
/// under a porous bed does not carry the pond above the bed, while the gaps that a disordered pond
/// leaves in a column one spacing wide, which its neighbours fill, do not cut the pond's weight
/// (test porous/a_gap_that_water_beside_fills_does_not_cut_the_column). Used instead of the
/// weakly compressible SPH pressure where water meets a rigid porous body: the pore water is incompressible and feels the pond's weight, not the acoustic noise of
/// the Tait pressure (a few hundred Pa at c = 15 m/s, as much as the head of a shallow pond).
/// Zero for particles that are not water.
/// `ranks`: the scene is decomposed; every rank's water particles make the columns (gathered, each
/// column in the one-process order), and ps's own particles and halo get their values.
template <int D>
std::vector<double> water_column_pressure(const ParticleSet<D>& ps, double spacing, double full_mass,
                                          double fluid_density, double gravity, const Decomposition<D>* ranks = nullptr);

/// Pressure of the pond at a porous particle i in contact with water: the column pressures of its
/// water neighbours carried to x_i hydrostatically, Σ_j W_ij (P_j + ρ^f g·(x_i − x_j)) / Σ_j W_ij
/// (the extrapolation of Adami et al. 2012, poly6 weights), at least 0.
template <int D>
double pond_pressure(const ParticleSet<D>& ps, const NeighbourGrid<D>& nb, const std::vector<double>& column,
                     std::size_t i, double fluid_density, const Vec<D>& gravity);

/// `ranks`: the scene is decomposed (role, suction, P and the positions current in the halo);
/// every rank's rows of the system are gathered and every rank solves the one-process system,
/// rows in the order of the keys, and sets P at its own particles and halo.
template <int D>
void solve_harmonic_pressure(const ParticleSet<D>& ps, const NeighbourGrid<D>& nb,
                             const std::vector<PressureRole>& role, const std::vector<double>& suction,
                             double fluid_density, const Vec<D>& gravity, std::vector<double>& P,
                             const Decomposition<D>* ranks = nullptr);

}  // namespace sc
