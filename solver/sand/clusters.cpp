#include "sand/clusters.hpp"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace sc {

namespace {

/// Members per chunk of the sums of cluster_motions.
constexpr std::size_t kMembersPerChunk = 512;

}  // namespace

template <int D>
void find_clusters(ParticleSet<D>& ps, const NeighbourGrid<D>& nb, Clusters& clusters) {
  // -1 marks the particles that never join (all but rigid sand); they get 0 (no cluster) back at the end.
  constexpr std::int32_t kNever = -1;
  const auto n = static_cast<std::int64_t>(ps.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) ps.cluster[i] = ps.phase_of(i) == Phase::Sand && ps.rigid[i] ? 0 : kNever;
  clusters.search(ps.size(), std::span(ps.cluster), [&](std::size_t i) { return nb.of(i); });
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) ps.cluster[i] = std::max(ps.cluster[i], 0);
}

template <int D>
void cluster_motions(const ParticleSet<D>& ps, const Clusters& clusters, double dt, InertiaForm form,
                     std::vector<ClusterMotion<D>>& motions, ClusterBuffers<D>& buffers) {
  auto& chunks = buffers.chunks;
  auto& first_chunk = buffers.first_chunk;
  auto& moments = buffers.moments;
  auto& sums = buffers.sums;
  chunks.clear();
  first_chunk.resize(clusters.size() + 1);
  for (std::size_t c = 0; c < clusters.size(); ++c) {
    first_chunk[c] = chunks.size();
    for (std::size_t f = 0; f < clusters[c].size(); f += kMembersPerChunk) chunks.push_back({c, f});
  }
  first_chunk[clusters.size()] = chunks.size();
  auto members_of = [&](const typename ClusterBuffers<D>::Chunk& k) {
    const std::span<const std::size_t> all = clusters[k.cluster];
    return all.subspan(k.first, std::min(kMembersPerChunk, all.size() - k.first));
  };
  auto add_chunks = [&](const auto& parts, std::size_t c) {
    auto total = parts[first_chunk[c]];
    for (std::size_t k = first_chunk[c] + 1; k < first_chunk[c + 1]; ++k) total += parts[k];
    return total;
  };
  const auto nk = static_cast<std::int64_t>(chunks.size()), nc = static_cast<std::int64_t>(clusters.size());
  moments.resize(chunks.size());
  sums.resize(chunks.size());
  motions.resize(clusters.size());
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
      motions[c].mass = mass;
      motions[c].centre = first_moment / mass;
    }
#pragma omp for schedule(dynamic, 16)
    for (std::int64_t k = 0; k < nk; ++k)
      sums[k] = motion_sums<D>(members_of(chunks[k]), ps.m, ps.x, ps.v, ps.force, motions[chunks[k].cluster].centre, form);
#pragma omp for schedule(static)
    for (std::int64_t c = 0; c < nc; ++c)
      motions[c] = motion_from_sums<D>(motions[c].mass, motions[c].centre, add_chunks(sums, c), dt, clusters[c].size() > 1);
  }
}

template <int D>
void move_clusters(ParticleSet<D>& ps, const Clusters& clusters, const std::vector<ClusterMotion<D>>& motions,
                   double dt, double damping, ClusterBuffers<D>& buffers) {
  // The turn of every cluster first, then every member on its own (ps.cluster names its cluster),
  // so the members of one large cluster are shared among the threads.
  auto& turns = buffers.turns;
  turns.resize(clusters.size());
  const auto nc = static_cast<std::int64_t>(clusters.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t c = 0; c < nc; ++c) turns[c] = free_turn<D>(motions[c].inertia, motions[c].omega, dt);
  const auto n = static_cast<std::int64_t>(ps.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    if (ps.cluster[i] == 0) continue;
    const auto c = static_cast<std::size_t>(ps.cluster[i] - 1);
    const ClusterMotion<D>& motion = motions[c];
    const Vec<D> centre = motion.centre + dt * motion.velocity;
    ps.x[i] = rigid_position<D>(motion, turns[c].rotation, ps.x[i], dt);
    ps.v[i] = damping * (motion.velocity + spin_velocity<D>(turns[c].omega, ps.x[i] - centre));
  }
}

template void find_clusters<2>(ParticleSet<2>&, const NeighbourGrid<2>&, Clusters&);
template void find_clusters<3>(ParticleSet<3>&, const NeighbourGrid<3>&, Clusters&);
template void cluster_motions<2>(const ParticleSet<2>&, const Clusters&, double, InertiaForm,
                                 std::vector<ClusterMotion<2>>&, ClusterBuffers<2>&);
template void cluster_motions<3>(const ParticleSet<3>&, const Clusters&, double, InertiaForm,
                                 std::vector<ClusterMotion<3>>&, ClusterBuffers<3>&);
template void move_clusters<2>(ParticleSet<2>&, const Clusters&, const std::vector<ClusterMotion<2>>&, double, double,
                               ClusterBuffers<2>&);
template void move_clusters<3>(ParticleSet<3>&, const Clusters&, const std::vector<ClusterMotion<3>>&, double, double,
                               ClusterBuffers<3>&);

}  // namespace sc
