// Non-penetration of rigid sand clusters against solid walls: the contact of a rigid body with a
// fixed obstacle at the velocity level (Baraff 2001, "Rigid body simulation II: nonpenetration
// constraints"; Zhu & Bridson 2005 enforce u·n ≥ 0 at solid boundaries before they project rigid
// groups; the thesis' "solve collisions" step, Fig. 3.6 line 8).
//
// Why: a rigid cluster keeps its inter-particle distances, so its own pressure cannot rise to carry
// it; only the pair forces of the wall particles can (the extrapolated wall pressure and the Bell
// contact, whose stiffness is set per particle). Under a tall cluster resting on a few grains these
// are far too soft: each grain carries many times its own weight, the per-grain contact needs an
// overlap of a large part of a spacing to do so, and the cluster sinks through the wall layers
// (tests sand/rigid_block_resting_on_a_floor_is_carried_by_its_wall_contacts and
// sand/rigid_sand_mushroom_stands_on_its_stem_at_the_thesis_step).
#pragma once
#include <cmath>
#include <span>
#include <vector>

#include "core/particle_set.hpp"
#include "neighbours/neighbour_grid.hpp"
#include "sand/clusters.hpp"
#include "sand/rigid_body.hpp"

namespace sc {

/// One contact of a cluster member with a solid wall particle: the member must not come closer
/// to the wall particle than their contact distance s = (s_i + s_w)/2 (the distance of the Bell
/// contact, sand_forces.cpp), i.e. the wall is the union of its particles' spheres.
template <int D>
struct WallContact {
  Vec<D> arm = Vec<D>::Zero();     ///< member position minus the cluster centre [m]
  Vec<D> normal = Vec<D>::Zero();  ///< unit vector from the wall particle to the member
  double gap = 0.0;                ///< |x_i − x_w| − s [m]; negative: overlap
  bool rough = false;              ///< no-slip wall: Coulomb friction at the contact
};

/// The contacts of the members of one cluster with the solid (non-porous) wall particles among
/// their neighbours, in member order and neighbour-list order (deterministic), whose gap is at most
/// `max_gap` [m]. The arms are taken about `centre`.
template <int D>
std::vector<WallContact<D>> cluster_wall_contacts(const ParticleSet<D>& ps, const NeighbourGrid<D>& nb,
                                                  std::span<const std::size_t> members, const Vec<D>& centre,
                                                  double max_gap = INFINITY);

/// Result of resolve_wall_contacts: the impulses the walls gave the cluster in the step.
template <int D>
struct ContactImpulse {
  Vec<D> normal = Vec<D>::Zero();      ///< Σ λ_n n [N s]
  Vec<D> tangential = Vec<D>::Zero();  ///< Σ friction impulses [N s]
  int iterations = 0;
};

/// Makes the end-of-step rigid motion of a cluster (rigid_motion, eqs 15-18) respect its wall
/// contacts over the step Δt: at every contact k the velocity of the member, u_k = v_cm + ω × r_k,
/// may approach the wall at most by the gap, u_k·n_k ≥ −max(g_k, 0)/Δt (a contact that already
/// overlaps may not deepen; the Bell contact force pushes it out), by non-negative normal impulses
/// λ_k n_k at the contact points (Baraff 2001: impulses j n with effective mass
/// 1/(1/M + (r × n)ᵀ I⁻¹ (r × n)), restitution 0: resting contact). At a rough wall each contact
/// also takes a friction impulse against its tangential velocity, bounded by Coulomb's cone
/// |λ_t| ≤ μ λ_n (Zhu & Bridson's frictional boundary condition at the impulse level). The
/// impulses of many contacts on one body are found by projected Gauss-Seidel sweeps (sequential
/// impulses: each contact in turn, clamped accumulated impulses) until a sweep changes the body's
/// motion by at most `tolerance` times what all sweeps changed it (both measured as the largest
/// change of a contact point's velocity, |Δv| + |Δω| max|r_k|), or `max_sweeps`. The stop is on the
/// body's motion, which is unique, not on the impulses, which are not: a body on more contacts than
/// its degrees of freedom (a sculpture on hundreds of floor contacts has 6) has many impulse sets
/// with the same motion, and the sweeps keep moving load among them long after the motion has
/// converged (test sand/wall_contact_sweeps_stop_when_the_motion_has_converged). The walls are fixed, so
/// the impulses change the cluster's momentum and angular momentum (motion.momentum,
/// motion.angular_momentum, motion.velocity, motion.omega); they only remove kinetic energy.
/// `spins`: whether the body can rotate (false for a single particle, as in rigid_motion).
template <int D>
ContactImpulse<D> resolve_wall_contacts(ClusterMotion<D>& motion, std::span<const WallContact<D>> contacts, bool spins,
                                        double dt, double mu, double tolerance = 1e-10, int max_sweeps = 200);

/// How far from a wall particle a member of the cluster may be (its gap, [m]) for the contact to
/// enter the sweeps of step dt: twice the largest point speed |v_cm| + |ω| |r| of the members in the
/// cluster's unconstrained motion, times dt. A farther contact cannot close within the step, so its
/// impulse would stay zero; leaving it out keeps the sweeps to the few contacts that act.
template <int D>
double wall_contact_reach(const ParticleSet<D>& ps, std::span<const std::size_t> members, const ClusterMotion<D>& motion,
                          double dt);

/// The buffers of constrain_clusters_by_walls, kept from one step to the next so that a step
/// allocates only when it needs more room than any step before.
template <int D>
struct WallContactBuffers {
  struct Chunk {
    std::size_t cluster, first;  // a large cluster's members from `first`, a fixed number of them
  };
  std::vector<std::vector<WallContact<D>>> per_thread;  // the contacts of the cluster a thread sweeps
  std::vector<std::vector<WallContact<D>>> of_chunk;    // the contacts of each chunk of chunks
  std::vector<Chunk> chunks;                            // the large clusters' members in chunks, in order
  std::vector<double> reach;                            // each large cluster's wall_contact_reach
};

/// resolve_wall_contacts for every cluster, with the Coulomb coefficient mu of rough walls. Each
/// cluster's sweeps run on one thread and write only its motion, the clusters shared among the
/// threads; the contacts of a large cluster are gathered by fixed chunks of members in parallel and
/// joined in member order, so every cluster sees the same contacts in the same order at any number
/// of threads (test sand/wall_contacts_of_many_large_clusters_are_the_same_at_1_and_2_threads).
template <int D>
void constrain_clusters_by_walls(const ParticleSet<D>& ps, const NeighbourGrid<D>& nb, const Clusters& clusters,
                                 std::vector<ClusterMotion<D>>& motions, double dt, double mu,
                                 WallContactBuffers<D>& buffers);

}  // namespace sc
