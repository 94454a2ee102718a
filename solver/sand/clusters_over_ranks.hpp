// Rigid sand clusters of a scene decomposed over MPI ranks (parallel/decomposition.hpp): the
// clusters of find_clusters, their rigid motions (cluster_motions, eqs 13-18) and their wall
// contacts (constrain_clusters_by_walls), bitwise those of the one-process run (docs/scaling.md,
// "Rigid clusters over ranks").
//
// A cluster is a connected component and may span ranks; its sums must be added in the order of
// its members in the one-process breadth-first search. So every rank sends every rank its own rigid
// sand particles (key, mass, position, velocity, force), each with the keys of its rigid sand
// neighbours in neighbour-list order (its bonds) and its candidate wall contacts in neighbour-list
// order. A rank's own particles have the one-process neighbour lists (the halo holds every
// neighbour), so every rank then holds the rigid sand of the whole scene in key order (the
// one-process storage order) with the one-process lists restricted to it, and runs on it the
// one-process search, sums and contact sweeps: the same clusters with the same numbers, the same
// member order, every sum added in the same order. Nothing is reduced over the ranks: every rank
// computes every cluster's motion, and each moves its own members.
#pragma once
#include <vector>

#include "core/particle_set.hpp"
#include "neighbours/neighbour_grid.hpp"
#include "parallel/decomposition.hpp"
#include "sand/clusters.hpp"
#include "sand/rigid_wall_contact.hpp"

namespace sc {

template <int D>
class ClustersOverRanks {
 public:
  /// find_clusters over the ranks of `dd`: `ps` is this rank's particles followed by the halo
  /// (whose ps.rigid must be its owners'), `nb` their neighbour lists. Writes ps.cluster (the
  /// one-process numbers for this rank's own particles, 0 in the halo) and puts the clusters of
  /// the whole scene into `clusters`, whose members index the gathered rigid sand (not ps). Collective.
  void find(ParticleSet<D>& ps, const NeighbourGrid<D>& nb, const Decomposition<D>& dd, Clusters& clusters);
  /// cluster_motions and constrain_clusters_by_walls of `clusters`, the last find's, for step dt,
  /// from the gathered rigid sand: the same motions on every rank.
  std::vector<ClusterMotion<D>> motions(const Clusters& clusters, double dt, InertiaForm form, double mu) const;
  /// Clusters with members on more than one rank, summed over the calls of find.
  long across_ranks() const { return across_ranks_; }

 private:
  /// Puts the rigid sand of every rank's `received` bytes into rigid_ and walls_, in key order;
  /// returns each one's bonds (indices into rigid_) and source rank.
  void unpack(const std::vector<std::string>& received, std::vector<std::vector<std::size_t>>& bonds,
              std::vector<int>& source);

  ParticleSet<D> rigid_;                    // the gathered rigid sand in key order: m, x, v and force only
  std::vector<std::uint64_t> keys_;         // their keys, ascending
  std::vector<WallContact<D>> walls_;       // their candidate wall contacts (any gap; arm = own position)
  std::vector<std::size_t> first_wall_;     // particle k's contacts: walls_[first_wall_[k], first_wall_[k + 1])
  long across_ranks_ = 0;
};

}  // namespace sc
