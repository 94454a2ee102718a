// One step of porous flow (thesis §3.4-3.5 after Lenaerts et al. 2008): saturation, capillary and
// pore pressure, pore velocity, conserving diffusion of absorbed water, absorption of water
// particles and emission into water particles or new ones.
//
// Who takes part: porous particles (porosity > 0: moving sand, or a fixed porous skeleton of
// boundary-phase particles) and water particles with a porous neighbour (Lenaerts §4, thesis
// Fig. 3.7 cases B and C). A water particle gives water as a saturated porous particle (S = 1,
// φ = 1) and receives it as an unsaturated one with room up to a full-size particle's mass; its
// mass (hence its volume m/ρ) shrinks or grows with what it gives or gets, and it is deleted once
// it falls below `min_water_fraction` of a full particle (its rest goes to the porous neighbour
// with the most room). Water pairs exchange nothing; non-porous walls take no part.
// Deviation from Lenaerts (who also scale the support with the radius): the support radius stays
// that of a full particle. With the gather density of eq 6, ρ_i = Σ_j m_j W(r, h_i), a particle
// with a shrunken h_i next to a full one sees m0 W(r, h_i) ~ (m0/m_i) ρ0 and the Tait pressure
// explodes; a shrinking support needs the scatter density Σ_j m_j W(r, h_j), which the solver
// does not use.
//
// Emission into empty space (Lenaerts §4.2): a porous particle whose pore velocity points to an
// empty place one spacing away (no particle within 0.8 spacing) and whose capillary suction is
// below one spacing of water head (a seepage face: water leaves into air only where its pressure
// reaches the atmosphere's, ours [I]) sends the flow a full lattice half-space would take,
// S^β m_p |v_p| / s, into its emission store; once the store holds `create_fraction` of a full
// water particle, a water particle of at most a full particle's mass is created there (placed
// away from all particles, including those created earlier in the same step; the rest of a larger
// store waits for the next free target). Stores flow back into m_p while not exposed.
//
// Held water weighs (thesis §3.4: the absorbed fluid mass is taken into account in all
// computations; Lenaerts §4: particles gain weight): the mass m of moving porous sand is its dry
// mass plus its held water m_p + store (porous/wet_density.hpp), so gravity, inertia, the density
// sum and rigid clusters carry the water, and its rest density is that of [thesis eq. 31]. Every
// exchange of water between particles carries momentum: water given leaves at the giver's velocity,
// the receiver takes the mass-weighted mean, so Σ m v of water and moving sand is unchanged (test
// porous/absorption_and_emission_conserve_the_momentum_of_water_and_sand). A fixed porous bed keeps
// the mass of its wall model and velocity 0.
//
// Determinism: every loop over particles is a gather that writes only its own entries; pair
// flows are computed identically by both particles; deletions and creations are queued serially
// in index order.
#pragma once
#include "core/particle_set.hpp"
#include "neighbours/neighbour_grid.hpp"
#include "parallel/decomposition.hpp"
#include "porous/diffusion.hpp"
#include "porous/porous_params.hpp"
#include "porous/rigid_pore_pressure.hpp"

namespace sc {

/// Counts of the exchange in one step.
struct PorousStepCounts {
  std::size_t absorbed = 0;  ///< water particles deleted (fully absorbed)
  std::size_t created = 0;   ///< water particles created by emission
};

/// Per-particle and per-pair buffers of porous_step, held between steps so that a step does not
/// allocate (they are resized, and every entry a step reads is written by that step).
template <int D>
struct PorousWork {
  std::vector<ExchangeSlot<D>> slot;
  std::vector<std::uint8_t> part, porous, exposed, placeable, seepage, contact, flowing;
  std::vector<double> pc, pp, ghost, in, a, b, relaxed;
  std::vector<double> passed;   // water a particle passed on in the step (Δt × limited outflow) [kg]
  std::vector<double> suction;  // P^c of the pore-pressure solve (suction_after_step)
  std::vector<double> spacing;  // porous_spacing of porous particles (their volume does not change in a step)
  std::vector<double> taken;    // water a particle took in the diffusion of the step [kg]
  std::vector<double> rest_volume;  // m/ρ0 of moving porous sand at the start of the step [m^D]
  std::vector<double> to, from;  // Φ_{i→j}, Φ_{j→i} per neighbour-list entry
  std::vector<PressureRole> role;
  typename ParticleSet<D>::VecArray target;
  typename ParticleSet<D>::VecArray brought;  // Σ_j Δm_j v_j of the water it took [kg m/s]
  std::vector<std::size_t> emitters;  // the particle that queued each addition of the step, in queue order
};

/// Advances the absorbed water by dt. Deletions and creations are queued in `ps` (applied by
/// compact()). Fixed porous particles (boundary phase) keep φ = φ0; their P^p is the pore-water
/// pressure of a rigid skeleton (pond pressure in contact, storage relaxation when saturated).
/// `ranks`: the scene is decomposed (ps holds this rank's particles, then the halo with the
/// positions and velocities of this step): every value a pass reads from neighbours is refreshed
/// in the halo before it, the scene-wide parts (water columns, the pore-pressure solve, the
/// placement of new particles, the absorption of small ones) are gathered and done in the
/// one-process order, and only this rank's own particles queue removals and additions
/// (docs/scaling.md, "Porous flow").
template <int D>
PorousStepCounts porous_step(ParticleSet<D>& ps, const NeighbourGrid<D>& nb, const PorousParams& params,
                             const Vec<D>& gravity, double dt, PorousWork<D>& work, const Decomposition<D>* ranks = nullptr);

/// Water in the scene [kg]: water particle mass plus absorbed water (m_p and emission stores).
template <int D>
double total_water(const ParticleSet<D>& ps);

inline bool is_porous_phase(Phase phase, double porosity) { return phase != Phase::Water && porosity > 0.0; }

}  // namespace sc
