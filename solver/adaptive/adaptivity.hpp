// Adaptive sampling inside a run (thesis §3.6 after Adams et al. 2007): the case-file section
// "adaptive", the decision source (extended local feature size of the adapted particles, or a
// forced merge/split cycle for testing) and one adaptivity pass with its conservation account.
//
// Levels: level 0 is the case spacing (finest); a particle of level l has 2^l times the mass and
// 2^(l/D) times the support radius. The pass runs every `interval` steps, after the step's
// integration and porous exchange, and is applied with ParticleSet::compact() (stable order).
#pragma once
#include <optional>
#include <vector>

#include "adaptive/feature_size.hpp"
#include "adaptive/split_merge.hpp"
#include "core/particle_set.hpp"
#include "io/json_reader.hpp"
#include "neighbours/neighbour_grid.hpp"

namespace sc {

/// Forced cycles (testing conservation and recovery): in [0, until) the pass alternates every
/// half period between "merge everything mergeable" (elfs = +inf) and "split everything above the
/// finest level" (elfs = 0), starting with a merge half; from `until` on every particle is split
/// back to the finest level and stays there.
struct ForcedCycle {
  double period = 0.0;  ///< [s]
  double until = 0.0;   ///< [s]
};

/// Case-file section "adaptive" (documented in cases/README.md).
struct AdaptivitySpec {
  AdaptiveParams params;          ///< alpha, beta, levels; finest_volume is derived per spacing
  long interval = 10;             ///< steps between adaptivity passes
  double grid_cell = 1.0;         ///< background-grid node spacing / particle spacing (elfs)
  double blend_time = 0.005;      ///< [s] decay time of the density offsets (adaptive/density_blend.hpp)
  FeatureSizeParams feature;      ///< medial-axis detection; elfs clamps derived per spacing
  bool adapt_water = true, adapt_sand = false;  ///< phases that split and merge
  std::optional<ForcedCycle> forced;
};

/// Reads the "adaptive" object; `dim` for the hysteresis bound beta >= 2^(1/D) alpha.
AdaptivitySpec read_adaptivity(JsonObject o, int dim);

/// The elfs values that can decide anything, [0, band): a particle splits only if elfs < alpha r
/// (so below alpha r_max) and merges only if elfs > beta r at a level below max_level (so the
/// answer above beta r_(max_level-1) is always the same), plus 2 grid cells: elfs is 1-Lipschitz,
/// so when a particle's interpolated value is near a threshold, the grid nodes it is interpolated
/// from lie within sqrt(D) cells of it, inside the band. Used as the clamp and reach elfs_max of the
/// feature size (the narrow band: nodes further from the surface are not visited), so the
/// propagations visit only the band in which a decision can change, and every decision is the one
/// the unclamped elfs would give. With max_level = min_level nothing splits or merges, and the band is 2 cells.
template <int D>
double decision_band(const AdaptiveParams& params, double r_min, double grid_cell);

/// Derives the spacing-dependent values: finest_volume = level-0 m / rho0, the background grid
/// cell, the lfs cap (given in spacings), the elfs clamps [alpha r_min / 2, decision_band] and
/// the outside reach of the elfs (2 cells).
template <int D>
void derive_adaptivity(AdaptivitySpec& spec, double spacing, double finest_volume);

/// What the passes of a run did, and how well they conserved what they must.
struct AdaptAccount {
  long passes = 0;
  std::size_t splits = 0, merges = 0;
  double energy_removed = 0.0;        ///< Σ μ_r |v_1 − v_2|² / 2 over all merges [J]
  double max_mass_rel_error = 0.0;    ///< max over passes |ΔΣm| / Σm (moving particles)
  double max_momentum_error = 0.0;    ///< max over passes |ΔΣmv| / Σ m|v| (0 when at rest)
  double max_moment_error = 0.0;      ///< max over passes |ΔΣmx| / Σ m|x| (centre of mass)
  double max_water_rel_error = 0.0;   ///< free + absorbed water, max over passes |Δ| / total
};

/// Extended local feature size at every particle (NaN, "no decision", for particles that are not
/// adapted):
/// the adapted particles are a union of discs/balls of radius r_i = (m_i / ρ0_i)^(1/D); its
/// signed-distance function is sampled on a background grid, feature_size() runs there and the
/// result is interpolated back to the particles.
template <int D>
std::vector<double> particle_elfs(const ParticleSet<D>& ps, const AdaptivitySpec& spec);

/// What one pass changed, as indices of the particles before its compaction: the particles it
/// removed (ascending) and, for each particle it added (in the order ParticleSet::compact appends
/// them), the particle that queued it.
struct AdaptChanges {
  std::vector<std::size_t> removed, queued_by;
};

/// One adaptivity pass at time t: decides (elfs or the forced cycle), queues splits and merges,
/// applies them (ps.compact()), and adds counts and conservation errors to `account`.
/// `nb` must hold the lists of the current particle set (same size).
template <int D>
AdaptChanges adapt_particles(ParticleSet<D>& ps, const NeighbourGrid<D>& nb, const AdaptivitySpec& spec, double t,
                     AdaptAccount& account);

}  // namespace sc
