// Adaptive sampling (Adams et al. 2007, thesis §3.6): split one particle into two, merge a pair
// into one, the level bookkeeping and the split/merge decision with hysteresis.
//
// Every field of ParticleSet is carried by an explicit rule (`field_rule`); a field without a rule
// makes split and merge throw std::logic_error, so a new field must be classified before it can
// be used with adaptivity (test_adaptive checks that every current field is classified).
//
//   Extensive  split: halved;            merge: summed            (mass, absorbed water, ...)
//   Intensive  split: copied;            merge: mass-weighted     (velocity, density, S, ...)
//   Position   split: x +- delta e;      merge: mass-weighted     (centre of mass exact)
//   Size       split: h / 2^(1/D);       merge: (h1^D + h2^D)^(1/D)  (h^D ~ m / rho0)
//   Copy       split: copied;            merge: taken from the first particle (flags, phase)
//   Level      split: level - 1;         merge: level + 1         (both partners share a level)
//   Identity   split and merge: a fresh id from ParticleSet::append
//
// Particle size: a particle of level L stands for the rest volume 2^L finest_volume, so its size
// (sampling spacing) is r = (2^L finest_volume)^(1/D) and the mass of a full particle doubles per
// level. The level is kept in ParticleSet::level, not read from m / rho0: porous flow lowers the
// mass of a water particle it drains and rewrites its rest density, which says nothing of the
// sampling the particle belongs to.
#pragma once
#include <cstdint>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

#include "core/particle_set.hpp"

namespace sc {

enum class FieldRule { Extensive, Intensive, Position, Size, Copy, Level, Identity };

/// The split/merge rule of a ParticleSet field by its visit_fields name; throws std::logic_error
/// for a field that has not been classified.
FieldRule field_rule(std::string_view field_name);

struct AdaptiveParams {
  double alpha = 1.0;            ///< split if elfs < alpha r
  double beta = 2.0;             ///< merge if elfs > beta r; needs beta >= 2^(1/D) alpha
  int min_level = 0;             ///< no split at or below this level
  int max_level = 3;             ///< no merge at or above this level
  double finest_volume = 1.0;    ///< m / rho0 of a level-0 particle [m^D]
  double split_offset = 0.5;     ///< delta = split_offset * r_child
  double merge_distance = 1.5;   ///< merge only if |x_ij| < merge_distance * r (same level)
};

/// Throws std::invalid_argument unless 0 < alpha, beta >= 2^(1/D) alpha (no immediate re-merge
/// of split children, no immediate re-split of a merged particle), min_level <= max_level and the
/// remaining parameters are positive. In 3-D the bound is docs/equations.md §4.5's 2^(1/3) alpha; in
/// 2-D the size ratio per level is 2^(1/2), so the bound is sqrt(2) alpha.
template <int D>
void check_params(const AdaptiveParams& params);

enum class Decision { Keep, Split, Merge };

/// Size r = (2^level finest_volume)^(1/D) of a particle of the given level [m].
template <int D>
double size_of_level(int level, const AdaptiveParams& params);
/// Split if elfs < alpha r and level > min_level; merge if elfs > beta r and level < max_level,
/// with r the size of the level.
template <int D>
Decision decide(double elfs, int level, const AdaptiveParams& params);

/// Among a fixed set of candidate axes (8 in 2-D, the 13 lattice directions in 3-D), the unit e
/// that maximises the smallest distance from x +- delta e to the given points; ties keep the first
/// candidate, so the choice is deterministic.
template <int D>
Vec<D> split_direction(const Vec<D>& x, double delta,
                       std::span<const Vec<D>> others);

/// Appends the two children of particle i of `from` to `to` (usually from.additions()): x +- delta
/// e, every other field by its rule. Throws std::invalid_argument for a particle of level 0.
/// Returns the index of the first child in `to`.
template <int D>
std::size_t split_particle(const ParticleSet<D>& from, std::size_t i, const Vec<D>& e,
                           double delta, ParticleSet<D>& to);

/// Appends the merge of particles i and j of `from` to `to`. Throws std::invalid_argument if their
/// phases or levels differ. Returns the kinetic energy removed, mu_r |v_i - v_j|^2 / 2 [J].
template <int D>
double merge_pair(const ParticleSet<D>& from, std::size_t i, std::size_t j, ParticleSet<D>& to);

/// Greedy stable pairing of merge candidates: in ascending index order, each unpaired candidate
/// takes its nearest unpaired candidate (ties: lower index) of the same level and phase within
/// merge_distance * r. `neighbours(i)` lists the particles near i (any order).
template <int D, class Neighbours>
std::vector<std::pair<std::size_t, std::size_t>> pair_merge_candidates(
    const ParticleSet<D>& ps, const std::vector<std::size_t>& candidates,
    const AdaptiveParams& params, Neighbours&& neighbours);

/// Counts and the kinetic energy one adaptivity pass removed.
struct AdaptStats {
  std::size_t splits = 0;
  std::size_t merges = 0;
  double energy_removed = 0.0;  ///< sum of mu_r |dv|^2 / 2 over the merges [J]
  /// For each particle queued in ps.additions(), in queue order, the particle that queued it: the
  /// parent of a split child, the first of a merged pair (the compaction's account over MPI ranks).
  std::vector<std::size_t> queued_by;
};

/// One adaptivity pass over the moving particles, in index order: decides with elfs[i], queues
/// splits (direction away from neighbours(i)) and then the paired merges into ps.additions() and
/// the parents into queue_remove. The caller applies them with ps.compact().
template <int D, class Neighbours>
AdaptStats adapt_pass(ParticleSet<D>& ps, const std::vector<double>& elfs,
                      const AdaptiveParams& params, Neighbours&& neighbours);

// --- implementation of the pairing template ---------------------------------------------------

namespace detail {
template <int D>
bool mergeable(const ParticleSet<D>& ps, std::size_t i, std::size_t j,
               const AdaptiveParams& params) {
  if (ps.phase[i] != ps.phase[j]) return false;
  if (ps.level[i] != ps.level[j]) return false;
  const double reach = params.merge_distance * size_of_level<D>(ps.level[i], params);
  return (ps.x[i] - ps.x[j]).norm() < reach;
}

template <int D, class Neighbours>
void queue_split(ParticleSet<D>& ps, std::size_t i, const AdaptiveParams& params,
                 Neighbours&& neighbours) {
  typename ParticleSet<D>::VecArray others;
  for (auto j : neighbours(i))
    if (static_cast<std::size_t>(j) != i) others.push_back(ps.x[static_cast<std::size_t>(j)]);
  const double delta = params.split_offset * size_of_level<D>(ps.level[i] - 1, params);
  const Vec<D> e = split_direction<D>(ps.x[i], delta, std::span<const Vec<D>>(others));
  split_particle<D>(ps, i, e, delta, ps.additions());
  ps.queue_remove(i);
}
}  // namespace detail

template <int D, class Neighbours>
std::vector<std::pair<std::size_t, std::size_t>> pair_merge_candidates(
    const ParticleSet<D>& ps, const std::vector<std::size_t>& candidates,
    const AdaptiveParams& params, Neighbours&& neighbours) {
  std::vector<std::uint8_t> state(ps.size(), 0);  // 1 = candidate, 2 = paired
  for (std::size_t c : candidates) state[c] = 1;
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (state[i] != 1) continue;
    std::size_t best = i;
    double best_d = 0.0;
    for (auto j_raw : neighbours(i)) {
      const auto j = static_cast<std::size_t>(j_raw);
      if (j == i || state[j] != 1 || !detail::mergeable(ps, i, j, params)) continue;
      const double d = (ps.x[i] - ps.x[j]).squaredNorm();
      if (best == i || d < best_d || (d == best_d && j < best)) { best = j; best_d = d; }
    }
    if (best == i) continue;
    state[i] = state[best] = 2;
    pairs.emplace_back(i, best);
  }
  return pairs;
}


template <int D, class Neighbours>
AdaptStats adapt_pass(ParticleSet<D>& ps, const std::vector<double>& elfs,
                      const AdaptiveParams& params, Neighbours&& neighbours) {
  check_params<D>(params);
  AdaptStats stats;
  std::vector<std::size_t> merge_candidates;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (!ps.moves(i)) continue;
    const Decision d = decide<D>(elfs[i], ps.level[i], params);
    if (d == Decision::Merge) merge_candidates.push_back(i);
    if (d != Decision::Split) continue;
    detail::queue_split<D>(ps, i, params, neighbours);
    stats.queued_by.insert(stats.queued_by.end(), 2, i);
    ++stats.splits;
  }
  for (auto [i, j] : pair_merge_candidates<D>(ps, merge_candidates, params, neighbours)) {
    stats.energy_removed += merge_pair<D>(ps, i, j, ps.additions());
    stats.queued_by.push_back(i);
    ps.queue_remove(i);
    ps.queue_remove(j);
    ++stats.merges;
  }
  return stats;
}

}  // namespace sc
