#include "sand/rigid_wall_contact.hpp"

#include <algorithm>
#include <cmath>

#include <omp.h>

#include "sand/sand_forces.hpp"

namespace sc {

namespace {

/// The (pseudo-)inverse of the inertia tensor, column by column with solve_inertia, so a
/// degenerate cluster (members on a line) cannot spin about its degenerate axis; zero for a body
/// that cannot spin (one particle: its inertia is round-off, as in rigid_motion).
template <int D>
AngMat<D> inverse_inertia(const AngMat<D>& inertia, bool spins) {
  AngMat<D> inv = AngMat<D>::Zero();
  if (!spins) return inv;
  for (int k = 0; k < angular_dim<D>; ++k) inv.col(k) = solve_inertia<D>(inertia, AngMat<D>::Identity().col(k));
  return inv;
}

/// The rigid body of resolve_wall_contacts: mass, inverse inertia and the velocities it updates.
template <int D>
struct Body {
  double inv_mass;
  AngMat<D> inv_inertia;
  Vec<D> v;
  AngVec<D> omega;

  Vec<D> point_velocity(const Vec<D>& arm) const { return v + spin_velocity<D>(omega, arm); }
  /// 1 / effective mass of an impulse along the unit vector t at the arm r: 1/M + (r × t)ᵀ I⁻¹ (r × t).
  double inv_effective_mass(const Vec<D>& arm, const Vec<D>& t) const {
    const AngVec<D> rt = moment<D>(arm, t);
    return inv_mass + rt.dot(inv_inertia * rt);
  }
  /// The largest change of a member's velocity from the body's motion `other` to this one, for
  /// members at most `reach` from the centre: |Δv| + |Δω| reach [m/s].
  double point_speed_change(const Body& other, double reach) const {
    return (v - other.v).norm() + (omega - other.omega).norm() * reach;
  }
  void apply(const Vec<D>& arm, const Vec<D>& impulse) {
    v += inv_mass * impulse;
    omega += inv_inertia * moment<D>(arm, impulse);
  }
};

/// Coulomb friction impulse of one contact: the impulse that stops its tangential velocity,
/// added to the accumulated one and clamped to the cone |λ_t| ≤ μ λ_n, and applied to the body.
template <int D>
void friction_step(Body<D>& body, const WallContact<D>& c, Vec<D>& accumulated, double limit) {
  const Vec<D> u = body.point_velocity(c.arm);
  const Vec<D> ut = u - u.dot(c.normal) * c.normal;
  const double speed = ut.norm();
  Vec<D> target = accumulated;
  if (speed > 0.0) target -= (speed / body.inv_effective_mass(c.arm, ut / speed)) * (ut / speed);
  const double size = target.norm();
  if (size > limit) target *= limit / size;
  const Vec<D> change = target - accumulated;
  accumulated = target;
  body.apply(c.arm, change);
}

/// The sweeps' data of one contact: its allowed normal velocity −max(g, 0)/Δt and normal inverse
/// effective mass (fixed over the sweeps), and its accumulated normal and friction impulses.
template <int D>
struct ContactRow {
  double allowed;
  double normal_inv_mass;
  double normal;
  Vec<D> friction;
};

/// Contacts whose gap a member cannot close within the step at this many times the largest point
/// speed of the cluster's unconstrained motion are left out of the sweeps (wall_contact_reach): their
/// impulse would stay zero (the impulses of resting contact only take kinetic energy out of the
/// body). Without this every wall particle within a member's support would be a contact, and the
/// sweeps would run to their limit over tens of thousands of them.
constexpr double kContactReachFactor = 2.0;

/// Clusters of at least this many members have their contacts gathered by chunks of kChunk
/// members in parallel (fixed chunks joined in member order: the same contacts in the same order at
/// any number of threads); smaller clusters are gathered one per thread.
constexpr std::int64_t kLargeCluster = 2048;
constexpr std::size_t kChunk = 512;

/// The largest speed |v_cm| + |ω| |r| of a member of the cluster in its (unconstrained) motion.
template <int D>
double largest_point_speed(const ParticleSet<D>& ps, std::span<const std::size_t> members, const ClusterMotion<D>& motion) {
  double arm = 0.0;
  const auto n = static_cast<std::int64_t>(members.size());
  // A maximum: exact in any order, so the threads share only a large cluster's members.
#pragma omp parallel for schedule(static) reduction(max : arm) if (n >= kLargeCluster)
  for (std::int64_t k = 0; k < n; ++k) arm = std::max(arm, (ps.x[members[k]] - motion.centre).norm());
  return motion.velocity.norm() + motion.omega.norm() * arm;
}

}  // namespace

namespace {

/// cluster_wall_contacts, appended to `out` (whose storage a caller can keep between clusters).
template <int D>
void append_cluster_wall_contacts(const ParticleSet<D>& ps, const NeighbourGrid<D>& nb,
                                  std::span<const std::size_t> members, const Vec<D>& centre, double max_gap,
                                  std::vector<WallContact<D>>& out) {
  for (const auto i : members) {
    const double si = rest_spacing<D>(ps.m[i], ps.rho0[i]);
    NeighbourSpacing<D> spacing_of;
    for (const auto w : nb.of(i)) {
      if (ps.phase_of(w) != Phase::Boundary || ps.porosity_of(w) != 0.0) continue;
      const Vec<D> d = ps.x[i] - ps.x[w];
      const double r = d.norm();
      if (r <= 0.0) continue;
      const double s = 0.5 * (si + spacing_of(ps.m[w], ps.rho0[w]));
      if (r - s > max_gap) continue;
      out.push_back({Vec<D>(ps.x[i] - centre), Vec<D>(d / r), r - s, ps.rough[w] != 0});
    }
  }
}


}  // namespace

template <int D>
std::vector<WallContact<D>> cluster_wall_contacts(const ParticleSet<D>& ps, const NeighbourGrid<D>& nb,
                                                  std::span<const std::size_t> members, const Vec<D>& centre,
                                                  double max_gap) {
  std::vector<WallContact<D>> out;
  append_cluster_wall_contacts<D>(ps, nb, members, centre, max_gap, out);
  return out;
}

template <int D>
ContactImpulse<D> resolve_wall_contacts(ClusterMotion<D>& motion, std::span<const WallContact<D>> contacts, bool spins,
                                        double dt, double mu, double tolerance, int max_sweeps) {
  ContactImpulse<D> total;
  if (contacts.empty()) return total;
  Body<D> body{1.0 / motion.mass, inverse_inertia<D>(motion.inertia, spins), motion.velocity, motion.omega};
  // What stays fixed over the sweeps is set once; the buffer is kept between calls (per thread).
  thread_local std::vector<ContactRow<D>, Eigen::aligned_allocator<ContactRow<D>>> rows;
  rows.resize(contacts.size());
  for (std::size_t k = 0; k < contacts.size(); ++k)
    rows[k] = {-std::max(contacts[k].gap, 0.0) / dt, body.inv_effective_mass(contacts[k].arm, contacts[k].normal), 0.0,
               Vec<D>::Zero()};
  double reach = 0.0;
  for (const auto& c : contacts) reach = std::max(reach, c.arm.norm());
  const Body<D> start = body;
  for (int sweep = 0; sweep < max_sweeps; ++sweep) {
    const Body<D> before = body;
    for (std::size_t k = 0; k < contacts.size(); ++k) {
      const WallContact<D>& c = contacts[k];
      ContactRow<D>& row = rows[k];
      const double un = body.point_velocity(c.arm).dot(c.normal);
      const double lambda = std::max(0.0, row.normal + (row.allowed - un) / row.normal_inv_mass);
      body.apply(c.arm, (lambda - row.normal) * c.normal);
      row.normal = lambda;
      if (c.rough && mu > 0.0) friction_step<D>(body, c, row.friction, mu * lambda);
    }
    total.iterations = sweep + 1;
    if (body.point_speed_change(before, reach) <= tolerance * body.point_speed_change(start, reach)) break;
  }
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const double normal = rows[k].normal;
    const Vec<D>& friction = rows[k].friction;
    total.normal += normal * contacts[k].normal;
    total.tangential += friction;
    motion.momentum += normal * contacts[k].normal + friction;
    motion.angular_momentum += moment<D>(contacts[k].arm, Vec<D>(normal * contacts[k].normal + friction));
  }
  motion.velocity = body.v;
  motion.omega = body.omega;
  return total;
}

template <int D>
double wall_contact_reach(const ParticleSet<D>& ps, std::span<const std::size_t> members, const ClusterMotion<D>& motion,
                          double dt) {
  return kContactReachFactor * largest_point_speed<D>(ps, members, motion) * dt;
}

template <int D>
void constrain_clusters_by_walls(const ParticleSet<D>& ps, const NeighbourGrid<D>& nb, const Clusters& clusters,
                                 std::vector<ClusterMotion<D>>& motions, double dt, double mu,
                                 WallContactBuffers<D>& buffers) {
  const auto n = static_cast<std::int64_t>(clusters.size());
  const auto large = [&](std::int64_t c) { return std::ssize(clusters[c]) >= kLargeCluster; };
  buffers.per_thread.resize(std::max<std::size_t>(buffers.per_thread.size(), omp_get_max_threads()));
  buffers.reach.resize(clusters.size());
  buffers.chunks.clear();
  for (std::int64_t c = 0; c < n; ++c) {
    if (!large(c)) continue;
    buffers.reach[c] = wall_contact_reach<D>(ps, clusters[c], motions[c], dt);  // its members in parallel
    for (std::size_t first = 0; first < clusters[c].size(); first += kChunk)
      buffers.chunks.push_back({static_cast<std::size_t>(c), first});
  }
  buffers.of_chunk.resize(std::max(buffers.of_chunk.size(), buffers.chunks.size()));
  const auto nk = static_cast<std::int64_t>(buffers.chunks.size());
#pragma omp parallel
  {
#pragma omp for schedule(dynamic)
    for (std::int64_t k = 0; k < nk; ++k) {
      const auto [c, first] = buffers.chunks[k];
      const auto members = clusters[c].subspan(first, std::min(kChunk, clusters[c].size() - first));
      buffers.of_chunk[k].clear();
      append_cluster_wall_contacts<D>(ps, nb, members, motions[c].centre, buffers.reach[c], buffers.of_chunk[k]);
    }
    std::vector<WallContact<D>>& contacts = buffers.per_thread[omp_get_thread_num()];
    // The sweeps of the large clusters (at their first chunk) and of the small ones, a cluster per thread.
#pragma omp for schedule(dynamic, 1) nowait
    for (std::int64_t k = 0; k < nk; ++k) {
      const auto [c, first] = buffers.chunks[k];
      if (first != 0) continue;
      contacts.clear();
      for (std::int64_t part = k; part < nk && buffers.chunks[part].cluster == c; ++part)
        contacts.insert(contacts.end(), buffers.of_chunk[part].begin(), buffers.of_chunk[part].end());
      resolve_wall_contacts<D>(motions[c], contacts, true, dt, mu);
    }
#pragma omp for schedule(dynamic)
    for (std::int64_t c = 0; c < n; ++c) {
      if (large(c)) continue;
      const double reach = wall_contact_reach<D>(ps, clusters[c], motions[c], dt);
      contacts.clear();
      append_cluster_wall_contacts<D>(ps, nb, clusters[c], motions[c].centre, reach, contacts);
      resolve_wall_contacts<D>(motions[c], contacts, clusters[c].size() > 1, dt, mu);
    }
  }
}

#define SC_INSTANTIATE(D)                                                                                             \
  template std::vector<WallContact<D>> cluster_wall_contacts<D>(const ParticleSet<D>&, const NeighbourGrid<D>&,     \
                                                                std::span<const std::size_t>, const Vec<D>&, double); \
  template ContactImpulse<D> resolve_wall_contacts<D>(ClusterMotion<D>&, std::span<const WallContact<D>>, bool,     \
                                                      double, double, double, int);                                          \
  template double wall_contact_reach<D>(const ParticleSet<D>&, std::span<const std::size_t>, const ClusterMotion<D>&,  \
                                        double);                                                                      \
  template void constrain_clusters_by_walls<D>(const ParticleSet<D>&, const NeighbourGrid<D>&, const Clusters&,        \
                                               std::vector<ClusterMotion<D>>&, double, double, WallContactBuffers<D>&);
SC_INSTANTIATE(2)
SC_INSTANTIATE(3)
#undef SC_INSTANTIATE

}  // namespace sc
