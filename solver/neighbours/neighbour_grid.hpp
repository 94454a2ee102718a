// Uniform-grid neighbour search with per-particle support radii.
//
// Particles i and j are neighbours when |x_i - x_j| <= max(h_i, h_j) (thesis §3.6 after Adams
// 2007). The cell size is the largest support radius, so the 3^D cells around a particle's cell hold
// all its neighbours. Lists are stored once per step in compressed rows (CSR) and shared by every
// pass; each list includes the particle itself and is ordered by cell, then by index, so it does
// not depend on the number of threads.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "core/particle_set.hpp"

namespace sc {

template <int D>
class NeighbourGrid {
 public:
  /// Rebuilds the lists for the current positions and support radii.
  void rebuild(const ParticleSet<D>& particles);

  std::span<const std::uint32_t> of(std::size_t i) const {
    return {index_.data() + offset_[i], index_.data() + offset_[i + 1]};
  }
  std::size_t size() const { return offset_.empty() ? 0 : offset_.size() - 1; }
  std::size_t total_pairs() const { return index_.size(); }
  /// Particle indices sorted by grid cell (a cache-friendly order; see ParticleSet::permute).
  const std::vector<std::size_t>& cell_order() const { return sorted_; }

 private:
  std::vector<std::size_t> offset_;
  std::vector<std::uint32_t> index_;
  std::vector<std::size_t> sorted_;      // particle indices ordered by cell (stable)
  std::vector<std::size_t> cell_start_;  // start of each cell in sorted_
  std::vector<std::int64_t> cell_of_;
};

/// Brute-force O(N^2) twin with the same pair rule, for tests.
template <int D>
std::vector<std::vector<std::uint32_t>> brute_force_neighbours(const ParticleSet<D>& particles);

}  // namespace sc
