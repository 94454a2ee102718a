// Uniform-grid neighbour search with per-particle support radii.
//
// Particles i and j are neighbours when |x_i - x_j| <= max(h_i, h_j) (thesis §3.6 after Adams
// 2007). The cell size is the largest support radius, so the 3^D cells around a particle's cell hold
// all its neighbours. Lists are stored once per step in compressed rows (CSR, one buffer per chunk
// of particles) and shared by every pass; each list is ordered by cell, then within a cell by
// (inert last, index), so it does not depend on the number of threads. Pairs of two inert particles (ParticleSet::inert: fixed walls
// outside the porous flow) are left out, as no pass uses them; so the list of an inert particle
// holds only its non-inert neighbours, and every other list includes the particle itself.
//
// A rebuild is two calls: `bin` sorts the particles into cells, `find_pairs` builds the lists; in
// between, the particles can be put in storage_order() (then bin again). Fixed wall particles never
// move, so a step re-bins only the others (`bin_moving`) and keeps the walls' cells of the last
// `bin`, as long as the grid itself (bounds, cell size) is unchanged.
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "core/particle_set.hpp"
#include "neighbours/grid_geometry.hpp"

namespace sc {

template <int D>
class NeighbourGrid {
 public:
  /// Rebuilds the lists for the current positions and support radii (bin + find_pairs).
  void rebuild(const ParticleSet<D>& particles) {
    bin(particles);
    find_pairs(particles);
  }
  /// Sorts the particles into cells; the lists are not valid until find_pairs.
  void bin(const ParticleSet<D>& particles);
  /// bin() for particles whose inert ones (ParticleSet::inert) are those of the last bin(), at the
  /// same places and with the same supports: recomputes the cells of the others only. The inert
  /// particles are recognised by their ids, in index order: after a compaction that removed or added
  /// other particles they keep their cells; after a reorder (or any other change), bin() runs.
  void bin_moving(const ParticleSet<D>& particles);
  /// Builds the lists from the cells of the last bin() of the same particles.
  void find_pairs(const ParticleSet<D>& particles);
  /// From now on find_pairs lists the neighbours of the first `n` particles only and gives the
  /// others an empty list; they are still found as neighbours. A decomposed run's halo follows its
  /// own particles, and every value a halo particle sums is overwritten by its owner's before any
  /// other particle reads it (parallel/decomposition.hpp), so its lists would be work thrown away.
  /// SIZE_MAX (the default): every particle.
  void list_only_first(std::size_t n) { listed_ = n; }
  /// Bins on the grid of `bounds` from now on instead of the particles' own bounds (the bounds of
  /// the whole scene when the particles are one rank's part of it, parallel/decomposition.hpp), so
  /// that every rank's cells are the cells of the one-process grid; nullopt: the particles' own.
  void impose_bounds(const std::optional<GridBounds<D>>& bounds) { imposed_ = bounds; }
  /// The grid of the last bin().
  const GridGeometry<D>& geometry() const { return g_; }
  /// Bounds of the positions and largest support of the particles `which` (exact: any threads).
  static GridBounds<D> bounds(const ParticleSet<D>& ps, std::span<const std::uint32_t> which);

  /// The list of particle i, in its chunk's buffer.
  std::span<const std::uint32_t> of(std::size_t i) const {
    const std::size_t c = i / kChunk;
    const std::uint32_t* chunk = chunk_lists_[c].data();
    return {chunk + (offset_[i] - chunk_base_[c]), chunk + (offset_[i + 1] - chunk_base_[c])};
  }
  /// Position of of(i) in the concatenation of all lists (for data kept per list entry).
  std::size_t list_start(std::size_t i) const { return offset_[i]; }
  std::size_t size() const { return offset_.empty() ? 0 : offset_.size() - 1; }
  std::size_t total_pairs() const { return chunk_base_.empty() ? 0 : chunk_base_.back(); }
  /// A cache-friendly order for ParticleSet::permute, from the last bin(): the non-inert
  /// particles by cell, then the inert ones by cell (so the particles that move stay together).
  const std::vector<std::size_t>& storage_order();

 private:
  std::size_t append_neighbours(const ParticleSet<D>& ps, std::size_t i, std::vector<std::uint32_t>& out,
                                std::size_t used) const;
  /// inert_, moving_, fixed_ and the layout of the particles; sizes the per-particle arrays.
  void classify(const ParticleSet<D>& ps);
  using Bounds = GridBounds<D>;
  /// Grid from the bounds of all particles (or the imposed ones); true if it differs from the last one.
  bool set_grid(const Bounds& moving, const Bounds& fixed);
  /// Slot of particle i in the current grid (see slot_start_).
  std::uint64_t slot(const ParticleSet<D>& ps, std::size_t i) const;
  void sort_by_slot(const ParticleSet<D>& ps);
  void mark_cells_near_moving();

  // Particles per chunk of the pair search: chunks are the unit of work sharing, fixed in size so
  // the lists do not depend on the number of threads. Each chunk's lists stay in its own buffer
  // (no joined copy): offset_ holds positions in the concatenation of the chunks' used entries,
  // chunk_base_ where each chunk starts in it.
  static constexpr std::size_t kChunk = 512;
  std::vector<std::size_t> offset_;
  std::vector<std::vector<std::uint32_t>> chunk_lists_;  // per chunk of particles: its lists, then unused room
  std::vector<std::size_t> chunk_used_, chunk_base_;     // per chunk: entries used, start in the concatenation
  // Particle indices ordered by (cell, inert, index), and one padding entry that the pair scan,
  // which tests candidates two at a time, may read but never lists.
  std::vector<std::uint32_t> sorted_;
  std::vector<std::uint32_t> slot_start_; // start in sorted_ of slot 2c (non-inert of cell c) and 2c + 1 (inert)
  std::vector<std::uint64_t> slot_of_;    // slot of each particle
  std::vector<std::uint8_t> inert_;
  std::vector<std::uint32_t> moving_, fixed_;  // indices of the non-inert and of the inert particles
  Bounds fixed_bounds_{};                    // of the inert particles, at the last bin()
  std::vector<std::int64_t> fixed_id_;       // ids of the inert particles at the last bin(), in index order
  std::vector<std::uint64_t> fixed_slot_;    // and their slots
  std::uint64_t layout_ = 0;                 // ParticleSet::layout at the last binning
  bool binned_ = false;                      // bin() has run: the walls' cache is valid
  std::vector<std::uint8_t> near_moving_, spread_;  // per cell: a non-inert particle in the 3^D block (bin)
  // Candidates of the pair search in sorted_ order (with its padding), one array per coordinate
  // and one of squared supports, so that the distance test runs on four candidates at once (two
  // without AVX).
  std::array<std::vector<double>, D> cx_;
  std::vector<double> ch2_;
  std::vector<std::uint32_t> part_start_;   // per part of the slots: start in sorted_ (sort_by_slot)
  std::vector<std::uint32_t> block_count_;  // per block of particles and slot: counts, then fill positions (bin)
  GridGeometry<D> g_;
  std::optional<Bounds> imposed_;
  std::size_t listed_ = SIZE_MAX;  // particles from this index on get an empty list (list_only_first)
  std::vector<std::size_t> storage_order_;
};

/// Brute-force O(N^2) twin with the same pair rule, for tests.
template <int D>
std::vector<std::vector<std::uint32_t>> brute_force_neighbours(const ParticleSet<D>& particles);

}  // namespace sc
