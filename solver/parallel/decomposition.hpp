// One SPH scene decomposed over MPI ranks: slabs of the neighbour grid's cells along the longest
// axis of the scene, a halo of the particles one cell layer around each slab, and migration of the
// particles that cross a slab's border (docs/scaling.md).
//
// Results do not depend on the number of ranks, bitwise. A particle's sums run over its neighbour
// list, which the grid orders by cell, then (inert last) by the particles' order in storage; so
// every cell's particles must lie in storage in the order the one-process run stores them. Each
// particle carries its position in that storage as its key: the scene's index at the start, and at
// each storage sort of the simulator (Simulator::kSortEvery) its place in the one-process sort — its
// slot (inert, cell) first, then its old key — computed from the counts of the rows of slots summed
// over all ranks and over the lower ranks (sort_keys). A slab is a whole number of cell layers, so a cell's particles all belong to one rank:
// every rank keeps its own particles in key order and appends the halo after them, each source
// rank's in key order. Every collective is exact: minima and maxima (the grid's bounds, the step
// size), integer sums (counts), and copies of bytes.
#pragma once
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "core/particle_set.hpp"
#include "neighbours/grid_geometry.hpp"
#include "parallel/comm.hpp"

namespace sc {

/// What the decomposition did, summed over the ranks.
struct DecompositionAccount {
  int ranks = 1;
  long rebalances = 0;      ///< slab choices that moved a border (every Decomposition::kRebalanceEvery steps at most; the first included)
  long migrated = 0;        ///< particles that moved to another rank's slab
  long halo_particles = 0;  ///< halo copies received, over all steps
  long clusters_across_ranks = 0;  ///< rigid sand clusters with members on several ranks, over all steps (sand/clusters_over_ranks.hpp)
  long removed = 0, added = 0;  ///< particles removed and added at compactions (Decomposition::compact)
  long at_border = 0;  ///< of those, removals and additions by a particle that another rank held a halo copy of
  long steps = 0;
};

/// Where a particle queued for creation stands in the one-process queue. The one process queues
/// additions in the storage order of the particles that queue them (ParticleSet::compact appends
/// them in queue order), so the order is the key of the particle that queued it, then its place in
/// its rank's queue (one particle's additions are all queued on the rank that owns it).
struct AdditionOrder {
  std::uint64_t queuer = 0, place = 0;
  auto operator<=>(const AdditionOrder&) const = default;
};

/// One rank's part of a compaction: how many particles it holds before it (no halo), the keys of
/// those it removes, and the order of those it adds (in its queue's order).
struct CompactionNotice {
  std::uint64_t particles = 0;
  std::vector<std::uint64_t> removed;
  std::vector<AdditionOrder> added;
};

/// Keys after a compaction, on one rank: `kept` its surviving particles' new keys, `added` its
/// additions' (in its queue's order); `survivors`, `additions`: the totals over the ranks.
struct CompactionKeys {
  std::vector<std::uint64_t> kept, added;
  std::uint64_t survivors = 0, additions = 0;
};

/// The one-process indices after ParticleSet::compact (removals in index order, then additions in
/// queue order) of one rank's particles, from every rank's notice (`every_rank`; the keys before
/// it were the one-process indices 0..N−1). A survivor's new key is the number of survivors with
/// a smaller key on any rank: its old key less the removed keys below it. An addition's is the
/// number of survivors plus its place among every rank's additions sorted by AdditionOrder.
/// `kept`: this rank's survivors' old keys; `mine`: its additions' orders. Exact integer
/// arithmetic. Test: decomposition/compaction_keys_are_the_one_process_indices_after_compact.
CompactionKeys compaction_keys(const std::vector<std::uint64_t>& kept, const std::vector<AdditionOrder>& mine,
                               const std::vector<CompactionNotice>& every_rank);

template <int D>
class Decomposition {
 public:
  /// Steps between two choices of the slabs (by particle count).
  static constexpr long kRebalanceEvery = 8;

  explicit Decomposition(Comm comm) : comm_(comm) {}
  const Comm& comm() const { return comm_; }

  /// `ps`, the whole scene in its one-process order (the same on every rank), becomes this rank's
  /// share; the keys are the scene's indices.
  void scatter(ParticleSet<D>& ps);
  /// Start of step `step` on this rank's particles `ps` (no halo): the bounds of the whole scene
  /// (bounds()), new slabs every kRebalanceEvery steps, migration of the particles whose cell lies
  /// in another rank's slab, and, when `sort` (a storage sort of the simulator), the new keys of
  /// the one-process sort with `ps` put in their order.
  void begin_step(ParticleSet<D>& ps, long step, bool sort);
  /// Adds the halo to `ps`, after this rank's own particles: a copy of every other rank's particles
  /// in the cell layers next to this rank's slab, each rank's in key order.
  void add_halo(ParticleSet<D>& ps);
  /// Removes the halo from `ps` again.
  void drop_halo(ParticleSet<D>& ps);
  /// End of a step that may remove or add particles: drops the halo, applies the removals and
  /// additions queued in `ps` (its own particles' only) as ParticleSet::compact does, and gives
  /// every particle its one-process index after the compaction as its key (compaction_keys) and
  /// each addition the id the one process gives it. `queued_by[k]`: the index in `ps` of the
  /// particle that queued addition k. Collective.
  void compact(ParticleSet<D>& ps, const std::vector<std::size_t>& queued_by);
  /// Mid-step, after a compaction done on the whole scene on every rank (adaptive sampling): `ps`,
  /// this rank's particles with their halo, becomes this rank's share of `whole`, the scene in its
  /// one-process order after the compaction (the same on every rank): keys are its indices, the
  /// bounds its bounds, the slabs kept; then a new halo is added. `removed` and `queued_by` are the
  /// compaction's (AdaptChanges: indices before it, which were the keys) and count in the account
  /// where this rank owned the particles. Collective.
  void adopt(ParticleSet<D>& ps, ParticleSet<D> whole, const std::vector<std::size_t>& removed,
             const std::vector<std::size_t>& queued_by);
  /// Keeps the keys of this rank's own particles as they stand at the start of a step (before the
  /// halo): the keys of the blow-up guard's last good state.
  void save_last_good_keys() { last_good_key_ = key_; }
  /// Puts the kept keys back, as the blow-up guard puts this rank's particles back to their last
  /// good state: a compaction in the failed step gave the particles new keys, and gather() and the
  /// checkpoint order the last good state by its own. Test: decomposition/a_blow_up_in_a_step_with_an_adaptivity_pass_over_2_and_3_ranks_is_reported_as_in_one_process.
  void restore_last_good_keys() {
    key_ = last_good_key_;
    own_ = kNoHalo;
  }
  /// Overwrites the halo's values of `field` (one entry per particle of `ps` with its halo) with
  /// their owners' values.
  template <class Field>
  void refresh(Field& field) const;

  /// Whether particle i of `ps` is a halo copy (the halo follows this rank's own particles).
  bool is_halo(std::size_t i) const { return i >= own_; }
  /// The number of this rank's own particles, which come first in `ps` during a step (SIZE_MAX outside one).
  std::size_t own() const { return own_; }
  /// Bounds of the whole scene at the start of the step (all ranks' particles).
  const GridBounds<D>& bounds() const { return bounds_; }
  /// The key (place in the one-process storage order) of particle i of `ps`.
  std::uint64_t key(std::size_t i) const { return key_[i]; }
  /// Every rank's particles `owned` in the one-process order, on every rank; during a step the
  /// halo after a rank's own particles is left out. Collective.
  ParticleSet<D> gather(const ParticleSet<D>& owned) const;
  /// The account summed over the ranks. Collective.
  DecompositionAccount totals() const;
  /// Every rank's `mine` (structs of numbers and fixed-size vectors, copied as bytes), concatenated
  /// in rank order, on every rank. Collective.
  template <class T>
  std::vector<T> all_gather_plain(const std::vector<T>& mine) const;

 private:
  /// The rank whose slab holds axis cell coordinate c.
  int owner(std::int64_t c) const;
  /// Global bounds and grid of `ps`'s particles; `global`: ps is the whole scene on every rank.
  void find_grid(const ParticleSet<D>& ps, bool global);
  /// New slabs along the longest axis of the bounds, each with an equal share of the moving
  /// particles of `ps` counted per cell layer (summed over the ranks unless `global`). The inert
  /// walls are not counted: their cells are binned once and they take part in no sum of their own
  /// away from the moving particles, so the moving particles are the work.
  void rebalance(const ParticleSet<D>& ps, bool global);
  /// The one-process storage sort's keys for `ps`, then ps in their order.
  void sort_keys(ParticleSet<D>& ps);
  /// Appends the particles `received` (packed, each with its key) to ps and the keys.
  void append(ParticleSet<D>& ps, const std::vector<std::string>& received);
  /// For each of this rank's `own` particles, 1 if another rank holds a halo copy of it.
  std::vector<std::uint8_t> sent_flags(std::size_t own) const;
  /// Puts ps and the keys in `order` (new index k holds old order[k]; particles left out are dropped).
  void reorder(ParticleSet<D>& ps, const std::vector<std::size_t>& order);
  static constexpr std::size_t kNoHalo = SIZE_MAX;

  Comm comm_;
  GridBounds<D> bounds_ = GridBounds<D>::empty();
  GridGeometry<D> grid_;
  int axis_ = 0;
  std::vector<std::int64_t> cut_;  // rank r's slab: axis cells [cut_[r - 1], cut_[r]) (r = 0: from −∞; last: to +∞)
  std::vector<std::uint64_t> key_, last_good_key_;
  std::vector<std::uint32_t> all_;  // 0, 1, ..., n - 1 for this rank's n particles (find_grid)
  std::size_t own_ = kNoHalo;  // during a step: this rank's own particles, the halo after them
  std::vector<std::vector<std::uint32_t>> send_, recv_;  // per rank: indices of ps sent to it / received from it in the halo
  DecompositionAccount account_;
};

/// The raw bytes of one particle field's value (a number, or a fixed-size Eigen vector or matrix).
/// A struct of numbers and fixed-size vectors (no data(), no pointers) is its own bytes.
template <class T>
const void* field_bytes(const T& v) {
  if constexpr (std::is_arithmetic_v<T>) return &v;
  else if constexpr (requires { v.data(); }) return v.data();
  else return &v;
}
template <class T>
void* field_bytes(T& v) {
  if constexpr (std::is_arithmetic_v<T>) return &v;
  else if constexpr (requires { v.data(); }) return v.data();
  else return &v;
}

template <int D>
template <class Field>
void Decomposition<D>::refresh(Field& field) const {
  using T = typename Field::value_type;
  std::vector<std::string> send(send_.size());
  for (std::size_t r = 0; r < send_.size(); ++r) {
    send[r].resize(send_[r].size() * sizeof(T));
    for (std::size_t k = 0; k < send_[r].size(); ++k) std::memcpy(send[r].data() + k * sizeof(T), field_bytes(field[send_[r][k]]), sizeof(T));
  }
  const std::vector<std::string> got = comm_.exchange(send);
  for (std::size_t r = 0; r < recv_.size(); ++r)
    for (std::size_t k = 0; k < recv_[r].size(); ++k) std::memcpy(field_bytes(field[recv_[r][k]]), got[r].data() + k * sizeof(T), sizeof(T));
}

template <int D>
template <class T>
std::vector<T> Decomposition<D>::all_gather_plain(const std::vector<T>& mine) const {
  std::string bytes(mine.size() * sizeof(T), '\0');
  if (!mine.empty()) std::memcpy(bytes.data(), mine.data(), bytes.size());
  std::vector<T> all;
  for (const std::string& got : comm_.all_gather(bytes)) {
    const std::size_t old = all.size();
    all.resize(old + got.size() / sizeof(T));
    if (!got.empty()) std::memcpy(static_cast<void*>(all.data() + old), got.data(), got.size());
  }
  return all;
}

}  // namespace sc
