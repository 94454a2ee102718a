#include "sand/clusters.hpp"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <limits>
#include <vector>

namespace sc {

namespace {

/// The root of a particle that joins no cluster (find_clusters).
constexpr std::uint32_t kNoCluster = std::numeric_limits<std::uint32_t>::max();

/// A forest over the particle indices in which every link points to a smaller index, so the root of
/// a tree is its smallest member whatever the order of the links. The links are relaxed atomics:
/// threads may link and shorten paths at the same time (integers only; the result does not depend
/// on the interleaving).
class MinRootForest {
 public:
  explicit MinRootForest(std::vector<std::uint32_t>& parent) : parent_(parent) {}

  /// The root of x's tree (path halving on the way).
  std::uint32_t root(std::uint32_t x) const {
    for (;;) {
      const std::uint32_t p = link(x).load(std::memory_order_relaxed);
      if (p == x) return x;
      const std::uint32_t g = link(p).load(std::memory_order_relaxed);
      if (g != p) link(x).store(g, std::memory_order_relaxed);  // g < p < x: still x's ancestor
      x = g;
    }
  }
  /// Joins the trees of a and b: the larger root is linked below the smaller one.
  void join(std::uint32_t a, std::uint32_t b) const {
    for (;;) {
      a = root(a);
      b = root(b);
      if (a == b) return;
      if (a < b) std::swap(a, b);
      std::uint32_t expected = a;  // fails if another thread linked a meanwhile: retry from the roots
      if (link(a).compare_exchange_weak(expected, b, std::memory_order_relaxed)) return;
    }
  }

 private:
  std::atomic_ref<std::uint32_t> link(std::uint32_t x) const { return std::atomic_ref<std::uint32_t>(parent_[x]); }
  std::vector<std::uint32_t>& parent_;
};

/// Members per chunk of the sums of cluster_motions.
constexpr std::size_t kMembersPerChunk = 512;

}  // namespace

template <int D>
Clusters find_clusters(ParticleSet<D>& ps, const NeighbourGrid<D>& nb) {
  const auto n = static_cast<std::int64_t>(ps.size());
  auto joins = [&ps](std::size_t i) { return ps.phase_of(i) == Phase::Sand && ps.rigid[i]; };
  std::vector<std::uint32_t> parent(ps.size()), root(ps.size(), kNoCluster);
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) parent[i] = static_cast<std::uint32_t>(i);
  const MinRootForest forest(parent);
  // Every pair of rigid neighbours once (the lists are symmetric).
#pragma omp parallel for schedule(dynamic, 1024)
  for (std::int64_t i = 0; i < n; ++i) {
    if (!joins(i)) continue;
    const auto self = static_cast<std::uint32_t>(i);
    for (const auto j : nb.of(i))
      if (j < self && joins(j)) forest.join(self, j);
  }
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i)
    if (joins(i)) root[i] = forest.root(static_cast<std::uint32_t>(i));
  // The clusters numbered by their smallest members (the roots) in increasing order, each listing
  // its members in increasing index order.
  std::vector<std::int32_t> number(ps.size(), 0);
  Clusters clusters;
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (root[i] == i) {
      clusters.emplace_back();
      number[i] = static_cast<std::int32_t>(clusters.size());
    }
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) ps.cluster[i] = root[i] == kNoCluster ? 0 : number[root[i]];
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (ps.cluster[i] != 0) clusters[ps.cluster[i] - 1].push_back(i);
  return clusters;
}

template <int D>
std::vector<ClusterMotion<D>> cluster_motions(const ParticleSet<D>& ps, const Clusters& clusters, double dt) {
  // The members of every cluster in fixed chunks (the same at any number of threads), summed chunk
  // by chunk in parallel and added in chunk order, so a large cluster is shared among the threads.
  struct Chunk {
    std::size_t cluster, first;
  };
  std::vector<Chunk> chunks;
  std::vector<std::size_t> first_chunk(clusters.size() + 1);
  for (std::size_t c = 0; c < clusters.size(); ++c) {
    first_chunk[c] = chunks.size();
    for (std::size_t f = 0; f < clusters[c].size(); f += kMembersPerChunk) chunks.push_back({c, f});
  }
  first_chunk[clusters.size()] = chunks.size();
  auto members_of = [&](const Chunk& k) {
    const std::span<const std::size_t> all(clusters[k.cluster]);
    return all.subspan(k.first, std::min(kMembersPerChunk, all.size() - k.first));
  };
  auto add_chunks = [&](const auto& parts, std::size_t c) {
    auto total = parts[first_chunk[c]];
    for (std::size_t k = first_chunk[c] + 1; k < first_chunk[c + 1]; ++k) total += parts[k];
    return total;
  };
  const auto nk = static_cast<std::int64_t>(chunks.size()), nc = static_cast<std::int64_t>(clusters.size());
  std::vector<std::pair<double, Vec<D>>, Eigen::aligned_allocator<std::pair<double, Vec<D>>>> moments(chunks.size());
  std::vector<MotionSums<D>, Eigen::aligned_allocator<MotionSums<D>>> sums(chunks.size());
  std::vector<ClusterMotion<D>> out(clusters.size());
#pragma omp parallel
  {
#pragma omp for schedule(dynamic, 16)
    for (std::int64_t k = 0; k < nk; ++k) moments[k] = mass_and_moment<D>(members_of(chunks[k]), ps.m, ps.x);
#pragma omp for schedule(static)
    for (std::int64_t c = 0; c < nc; ++c) {
      auto [mass, first_moment] = moments[first_chunk[c]];
      for (std::size_t k = first_chunk[c] + 1; k < first_chunk[c + 1]; ++k) {
        mass += moments[k].first;
        first_moment += moments[k].second;
      }
      out[c].mass = mass;
      out[c].centre = first_moment / mass;
    }
#pragma omp for schedule(dynamic, 16)
    for (std::int64_t k = 0; k < nk; ++k)
      sums[k] = motion_sums<D>(members_of(chunks[k]), ps.m, ps.x, ps.v, ps.force, out[chunks[k].cluster].centre);
#pragma omp for schedule(static)
    for (std::int64_t c = 0; c < nc; ++c)
      out[c] = motion_from_sums<D>(out[c].mass, out[c].centre, add_chunks(sums, c), dt, clusters[c].size() > 1);
  }
  return out;
}

template <int D>
void move_clusters(ParticleSet<D>& ps, const Clusters& clusters, const std::vector<ClusterMotion<D>>& motions,
                   double dt, double damping) {
  // The turn of every cluster first, then every member on its own (ps.cluster names its cluster),
  // so the members of one large cluster are shared among the threads.
  std::vector<Mat<D>, Eigen::aligned_allocator<Mat<D>>> turns(clusters.size());
  const auto nc = static_cast<std::int64_t>(clusters.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t c = 0; c < nc; ++c) turns[c] = rotation<D>(dt * motions[c].omega);
  const auto n = static_cast<std::int64_t>(ps.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    if (ps.cluster[i] == 0) continue;
    const auto c = static_cast<std::size_t>(ps.cluster[i] - 1);
    const ClusterMotion<D>& motion = motions[c];
    const Vec<D> centre = motion.centre + dt * motion.velocity;
    ps.x[i] = rigid_position<D>(motion, turns[c], ps.x[i], dt);
    ps.v[i] = damping * (motion.velocity + spin_velocity<D>(motion.omega, ps.x[i] - centre));
  }
}

template Clusters find_clusters<2>(ParticleSet<2>&, const NeighbourGrid<2>&);
template Clusters find_clusters<3>(ParticleSet<3>&, const NeighbourGrid<3>&);
template std::vector<ClusterMotion<2>> cluster_motions<2>(const ParticleSet<2>&, const Clusters&, double);
template std::vector<ClusterMotion<3>> cluster_motions<3>(const ParticleSet<3>&, const Clusters&, double);
template void move_clusters<2>(ParticleSet<2>&, const Clusters&, const std::vector<ClusterMotion<2>>&, double, double);
template void move_clusters<3>(ParticleSet<3>&, const Clusters&, const std::vector<ClusterMotion<3>>&, double, double);

}  // namespace sc
