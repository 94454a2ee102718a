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
Clusters find_clusters(ParticleSet<D>& ps, const NeighbourGrid<D>& nb) {
  // -1 marks the particles that never join (all but rigid sand), in parallel, so the serial
  // search below reads one field per neighbour; they get 0 (no cluster) back at the end.
  constexpr std::int32_t kNever = -1;
  const auto n = static_cast<std::int64_t>(ps.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) ps.cluster[i] = ps.phase_of(i) == Phase::Sand && ps.rigid[i] ? 0 : kNever;
  auto joins = [&](std::size_t i) { return ps.cluster[i] == 0; };
  Clusters clusters;
  for (std::size_t seed = 0; seed < ps.size(); ++seed) {
    if (!joins(seed)) continue;
    const auto number = static_cast<std::int32_t>(clusters.size() + 1);
    ps.cluster[seed] = number;
    std::vector<std::size_t>& members = clusters.emplace_back(1, seed);  // also the breadth-first queue
    for (std::size_t k = 0; k < members.size(); ++k) {
      const std::size_t i = members[k];
      for (const auto j : nb.of(i))
        if (joins(j)) {
          ps.cluster[j] = number;
          members.push_back(j);
        }
    }
  }
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) ps.cluster[i] = std::max(ps.cluster[i], 0);
  return clusters;
}

template <int D>
std::vector<ClusterMotion<D>> cluster_motions(const ParticleSet<D>& ps, const Clusters& clusters, double dt,
                                              InertiaForm form) {
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
      sums[k] = motion_sums<D>(members_of(chunks[k]), ps.m, ps.x, ps.v, ps.force, out[chunks[k].cluster].centre, form);
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
  std::vector<Turn<D>, Eigen::aligned_allocator<Turn<D>>> turns(clusters.size());
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

template Clusters find_clusters<2>(ParticleSet<2>&, const NeighbourGrid<2>&);
template Clusters find_clusters<3>(ParticleSet<3>&, const NeighbourGrid<3>&);
template std::vector<ClusterMotion<2>> cluster_motions<2>(const ParticleSet<2>&, const Clusters&, double, InertiaForm);
template std::vector<ClusterMotion<3>> cluster_motions<3>(const ParticleSet<3>&, const Clusters&, double, InertiaForm);
template void move_clusters<2>(ParticleSet<2>&, const Clusters&, const std::vector<ClusterMotion<2>>&, double, double);
template void move_clusters<3>(ParticleSet<3>&, const Clusters&, const std::vector<ClusterMotion<3>>&, double, double);

}  // namespace sc
