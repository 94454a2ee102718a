// Clusters of non-yielding sand and their rigid motion (thesis §3.3, Fig. 3.2; Zhu & Bridson 2005's
// "rigid groups"; Baraff 2001).
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "core/particle_set.hpp"
#include "neighbours/neighbour_grid.hpp"
#include "sand/rigid_body.hpp"

namespace sc {

/// The rigid clusters of a step, stored flat: the members of cluster c are operator[](c), in the
/// order of the breadth-first search that found them (search). The storage is kept from one search
/// to the next, so a step allocates only when it finds more clusters or members than any before.
class Clusters {
 public:
  Clusters() = default;
  /// One cluster of the given members, in their order.
  explicit Clusters(std::span<const std::size_t> members) { add(members); }

  std::size_t size() const { return first_.size() - 1; }
  bool empty() const { return size() == 0; }
  std::span<const std::size_t> operator[](std::size_t c) const {
    return {members_.data() + first_[c], first_[c + 1] - first_[c]};
  }
  /// No clusters (the storage is kept).
  void clear() {
    members_.clear();
    first_.resize(1);
  }
  /// Appends a cluster of the given members, in their order.
  void add(std::span<const std::size_t> members) {
    members_.insert(members_.end(), members.begin(), members.end());
    first_.push_back(members_.size());
  }

  /// Replaces the clusters by the connected sets of the nodes 0 .. n − 1 that join: number[i] is 0
  /// for a node that joins and negative for one that never does; bonds_of(i) lists the nodes linked
  /// to i. Breadth-first search: seeds in increasing index order, each member's bonds in their
  /// order, so a cluster's members come in the same order at any number of threads (the order of
  /// the sums over a cluster's members). Writes number[i] = cluster number + 1 for every member.
  /// Serial: a parallel search that keeps this order has to settle, level by level, which member
  /// lists each new one first, and that costs more than the search (docs/performance.md, "Serial
  /// parts of a step").
  template <class Bonds>
  void search(std::size_t n, std::span<std::int32_t> number, Bonds&& bonds_of) {
    clear();
    for (std::size_t seed = 0; seed < n; ++seed) {
      if (number[seed] != 0) continue;
      const auto c = static_cast<std::int32_t>(size() + 1);
      number[seed] = c;
      members_.push_back(seed);  // also the breadth-first queue
      for (std::size_t k = first_.back(); k < members_.size(); ++k)
        for (const auto j : bonds_of(members_[k]))
          if (number[j] == 0) {
            number[j] = c;
            members_.push_back(j);
          }
      first_.push_back(members_.size());
    }
  }

 private:
  std::vector<std::size_t> members_;   // every cluster's members, cluster after cluster
  std::vector<std::size_t> first_{0};  // cluster c: members_[first_[c], first_[c + 1])
};

/// Groups the rigid sand particles (ps.rigid) into `clusters`: two rigid particles belong to the same
/// cluster when they are neighbours (|x_ij| ≤ max(h_i, h_j), the thesis' h' ≤ h), by
/// Clusters::search (seeds in increasing index order, neighbours in list order). Writes ps.cluster
/// (number + 1, 0 for particles in no cluster).
template <int D>
void find_clusters(ParticleSet<D>& ps, const NeighbourGrid<D>& nb, Clusters& clusters);

/// The buffers of cluster_motions and move_clusters, kept from one step to the next so that a
/// step allocates only when it has more clusters or members than any step before.
template <int D>
struct ClusterBuffers {
  struct Chunk {
    std::size_t cluster, first;  // members first .. first + kMembersPerChunk of a cluster
  };
  std::vector<Chunk> chunks;             // every cluster's members in fixed chunks, in order
  std::vector<std::size_t> first_chunk;  // cluster c: chunks[first_chunk[c], first_chunk[c + 1])
  std::vector<std::pair<double, Vec<D>>, Eigen::aligned_allocator<std::pair<double, Vec<D>>>> moments;
  std::vector<MotionSums<D>, Eigen::aligned_allocator<MotionSums<D>>> sums;
  std::vector<Turn<D>, Eigen::aligned_allocator<Turn<D>>> turns;
};

/// Rigid motion of every cluster for a step dt (rigid_motion: eqs 13-18) from the velocities and
/// forces at the start of the step, with the inertia tensor of eq 17 in the given form, into
/// `motions` (one per cluster). The sums over a cluster's members go by fixed chunks of members
/// (the same at any number of threads), in parallel, and are added in chunk order, so a large
/// cluster is shared among the threads.
template <int D>
void cluster_motions(const ParticleSet<D>& ps, const Clusters& clusters, double dt, InertiaForm form,
                     std::vector<ClusterMotion<D>>& motions, ClusterBuffers<D>& buffers);

/// cluster_motions with buffers of its own.
template <int D>
std::vector<ClusterMotion<D>> cluster_motions(const ParticleSet<D>& ps, const Clusters& clusters, double dt,
                                              InertiaForm form = InertiaForm::Corrected) {
  std::vector<ClusterMotion<D>> motions;
  ClusterBuffers<D> buffers;
  cluster_motions<D>(ps, clusters, dt, form, motions, buffers);
  return motions;
}

/// Moves the members of every cluster rigidly by one step: x ← r_cm + Δt v_cm + R (x − r_cm), then
/// v ← damping (v_cm + ω' × (x − r_cm_new)), eq 18 in its corrected form, with R and ω' the
/// torque-free turn of the cluster (free_turn: L = Iω is carried through the step, so in 3-D ω
/// precesses and L stays). The members are found by ps.cluster (as find_clusters writes it).
template <int D>
void move_clusters(ParticleSet<D>& ps, const Clusters& clusters, const std::vector<ClusterMotion<D>>& motions,
                   double dt, double damping, ClusterBuffers<D>& buffers);

/// move_clusters with buffers of its own.
template <int D>
void move_clusters(ParticleSet<D>& ps, const Clusters& clusters, const std::vector<ClusterMotion<D>>& motions,
                   double dt, double damping) {
  ClusterBuffers<D> buffers;
  move_clusters<D>(ps, clusters, motions, dt, damping, buffers);
}

}  // namespace sc
