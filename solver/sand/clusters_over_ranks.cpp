#include "sand/clusters_over_ranks.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>

namespace sc {

namespace {

/// Appends the bytes of `value` (a number or a fixed-size Eigen vector) to `out`.
template <class T>
void put(std::string& out, const T& value) {
  out.append(static_cast<const char*>(field_bytes(value)), sizeof(T));
}

/// Reads the next value of type T from `in` at `at`, and moves `at` past it.
template <class T>
T take(const std::string& in, std::size_t& at) {
  T value;
  std::memcpy(field_bytes(value), in.data() + at, sizeof(T));
  at += sizeof(T);
  return value;
}

/// Whether particle i takes part in the clusters: rigid sand (as in find_clusters).
template <int D>
bool joins(const ParticleSet<D>& ps, std::size_t i) {
  return ps.phase_of(i) == Phase::Sand && ps.rigid[i];
}

/// One gathered rigid sand particle as it arrived, before the particles are put in key order.
template <int D>
struct Arrival {
  std::uint64_t key;
  double m;
  Vec<D> x, v, force;
  std::vector<std::uint64_t> bonds;
  std::vector<WallContact<D>> walls;
  int source;
};

/// This rank's own rigid sand particles of `ps`, packed in their order (key order): key, mass,
/// position, velocity, force, the counts of bonds and wall contacts, the bonds' keys, and each wall
/// contact's normal, gap and roughness.
template <int D>
std::string pack_rigid(const ParticleSet<D>& ps, const NeighbourGrid<D>& nb, const Decomposition<D>& dd) {
  std::string out;
  std::vector<std::uint64_t> bonds;
  for (std::size_t i = 0; i < ps.size() && !dd.is_halo(i); ++i) {
    if (!joins(ps, i)) continue;
    bonds.clear();
    for (const auto j : nb.of(i))
      if (j != i && joins(ps, j)) bonds.push_back(dd.key(j));
    const std::vector<WallContact<D>> walls = cluster_wall_contacts<D>(ps, nb, std::span(&i, 1), Vec<D>::Zero());
    put(out, dd.key(i));
    put(out, ps.m[i]);
    put(out, ps.x[i]);
    put(out, ps.v[i]);
    put(out, ps.force[i]);
    put(out, static_cast<std::uint64_t>(bonds.size()));
    put(out, static_cast<std::uint64_t>(walls.size()));
    for (const std::uint64_t k : bonds) put(out, k);
    for (const WallContact<D>& w : walls) {
      put(out, w.normal);
      put(out, w.gap);
      put(out, static_cast<std::uint8_t>(w.rough));
    }
  }
  return out;
}

/// The particles packed by pack_rigid on every rank, by source rank.
template <int D>
std::vector<Arrival<D>> unpack_rigid(const std::vector<std::string>& received) {
  std::vector<Arrival<D>> out;
  for (std::size_t r = 0; r < received.size(); ++r) {
    const std::string& in = received[r];
    for (std::size_t at = 0; at < in.size();) {
      Arrival<D>& a = out.emplace_back();
      a.source = static_cast<int>(r);
      a.key = take<std::uint64_t>(in, at);
      a.m = take<double>(in, at);
      a.x = take<Vec<D>>(in, at);
      a.v = take<Vec<D>>(in, at);
      a.force = take<Vec<D>>(in, at);
      a.bonds.resize(take<std::uint64_t>(in, at));
      a.walls.resize(take<std::uint64_t>(in, at));
      for (std::uint64_t& k : a.bonds) k = take<std::uint64_t>(in, at);
      for (WallContact<D>& w : a.walls) {
        w.normal = take<Vec<D>>(in, at);
        w.gap = take<double>(in, at);
        w.rough = take<std::uint8_t>(in, at) != 0;
      }
    }
  }
  return out;
}

}  // namespace

template <int D>
void ClustersOverRanks<D>::unpack(const std::vector<std::string>& received, std::vector<std::vector<std::size_t>>& bonds,
                                  std::vector<int>& source) {
  std::vector<Arrival<D>> arrived = unpack_rigid<D>(received);
  std::sort(arrived.begin(), arrived.end(), [](const Arrival<D>& a, const Arrival<D>& b) { return a.key < b.key; });
  const std::size_t n = arrived.size();
  rigid_ = ParticleSet<D>();
  rigid_.x.resize(n);
  rigid_.v.resize(n);
  rigid_.force.resize(n);
  rigid_.m.resize(n);
  keys_.resize(n);
  source.resize(n);
  walls_.clear();
  first_wall_.assign(1, 0);
  for (std::size_t k = 0; k < n; ++k) {
    const Arrival<D>& a = arrived[k];
    keys_[k] = a.key;
    rigid_.m[k] = a.m;
    rigid_.x[k] = a.x;
    rigid_.v[k] = a.v;
    rigid_.force[k] = a.force;
    source[k] = a.source;
    walls_.insert(walls_.end(), a.walls.begin(), a.walls.end());
    first_wall_.push_back(walls_.size());
  }
  // A bond's key is a rigid sand particle's, and every rank sent all of its own.
  bonds.assign(n, {});
  for (std::size_t k = 0; k < n; ++k)
    for (const std::uint64_t key : arrived[k].bonds)
      bonds[k].push_back(static_cast<std::size_t>(std::lower_bound(keys_.begin(), keys_.end(), key) - keys_.begin()));
}

template <int D>
void ClustersOverRanks<D>::find(ParticleSet<D>& ps, const NeighbourGrid<D>& nb, const Decomposition<D>& dd,
                                Clusters& clusters) {
  std::vector<std::vector<std::size_t>> bonds;
  std::vector<int> source;
  unpack(dd.comm().all_gather(pack_rigid<D>(ps, nb, dd)), bonds, source);
  // find_clusters' search: seeds in key order (the one-process index order), each particle's bonds
  // in its neighbour-list order.
  std::vector<std::int32_t> number(keys_.size(), 0);
  clusters.search(keys_.size(), std::span(number), [&](std::size_t k) -> const std::vector<std::size_t>& { return bonds[k]; });
  for (std::size_t c = 0; c < clusters.size(); ++c) {
    const auto members = clusters[c];
    across_ranks_ += std::any_of(members.begin(), members.end(), [&](std::size_t k) { return source[k] != source[members[0]]; });
  }
  for (std::size_t i = 0; i < ps.size(); ++i) {
    ps.cluster[i] = 0;
    if (dd.is_halo(i) || !joins(ps, i)) continue;
    ps.cluster[i] = number[std::lower_bound(keys_.begin(), keys_.end(), dd.key(i)) - keys_.begin()];
  }
}

template <int D>
std::vector<ClusterMotion<D>> ClustersOverRanks<D>::motions(const Clusters& clusters, double dt, InertiaForm form,
                                                            double mu) const {
  std::vector<ClusterMotion<D>> out = cluster_motions<D>(rigid_, clusters, dt, form);
  const auto nc = static_cast<std::int64_t>(clusters.size());
  // constrain_clusters_by_walls on the gathered contacts: those within the reach, in member order
  // and each member's neighbour-list order, with their arms about the cluster's centre.
#pragma omp parallel
  {
    std::vector<WallContact<D>> contacts;  // kept over this thread's clusters
#pragma omp for schedule(dynamic)
    for (std::int64_t c = 0; c < nc; ++c) {
      const double reach = wall_contact_reach<D>(rigid_, clusters[c], out[c], dt);
      contacts.clear();
      for (const std::size_t k : clusters[c])
        for (std::size_t w = first_wall_[k]; w < first_wall_[k + 1]; ++w) {
          if (walls_[w].gap > reach) continue;
          WallContact<D>& contact = contacts.emplace_back(walls_[w]);
          contact.arm = rigid_.x[k] - out[c].centre;
        }
      resolve_wall_contacts<D>(out[c], contacts, clusters[c].size() > 1, dt, mu);
    }
  }
  return out;
}

template class ClustersOverRanks<2>;
template class ClustersOverRanks<3>;

}  // namespace sc
