// Non-penetration of rigid sand clusters against solid walls: the contact of a rigid body with a
// fixed obstacle at the velocity level (Baraff 2001, "Rigid body simulation II: nonpenetration
// constraints"; Zhu & Bridson 2005 enforce u·n ≥ 0 at solid boundaries before they project rigid
// groups; the thesis' "solve collisions" step, Fig. 3.6 line 8).
//
// Why: a rigid cluster keeps its inter-particle distances, so its own pressure cannot rise to carry
// it; only the pair forces of the wall particles can (the extrapolated wall pressure and the Bell
// contact, whose stiffness is set per particle). Under a tall cluster these are far too soft: the
// 0.75 m sand figure of thesis_winnie_box stands on 73 grains, 8 N each, a Bell overlap of half a
// spacing; the whole cluster fell freely until the overlap built up, bounced on springs with a
// cluster damping ratio of 0.02 and went through the two wall layers (measured: 6 cm by t = 0.2 s).
#pragma once
#include <cmath>
#include <span>
#include <vector>

#include "core/particle_set.hpp"
#include "neighbours/neighbour_grid.hpp"
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
/// its degrees of freedom (thesis_duck: 337 contacts, 6 freedoms) has many impulse sets with the
/// same motion, and the sweeps keep moving load among them long after the motion has converged
/// (the duck at rest: its velocity settled to 1e-11 of the change within 50 sweeps while the
/// impulses still moved by 5e-3 of the largest at the old limit of 200 sweeps). The walls are fixed, so
/// the impulses change the cluster's momentum and angular momentum (motion.momentum,
/// motion.angular_momentum, motion.velocity, motion.omega); they only remove kinetic energy.
/// `spins`: whether the body can rotate (false for a single particle, as in rigid_motion).
template <int D>
ContactImpulse<D> resolve_wall_contacts(ClusterMotion<D>& motion, std::span<const WallContact<D>> contacts, bool spins,
                                        double dt, double mu, double tolerance = 1e-10, int max_sweeps = 200);

/// resolve_wall_contacts for every cluster (parallel over clusters; each writes only its motion),
/// with the Coulomb coefficient mu of rough walls.
template <int D>
void constrain_clusters_by_walls(const ParticleSet<D>& ps, const NeighbourGrid<D>& nb,
                                 std::span<const std::vector<std::size_t>> clusters,
                                 std::vector<ClusterMotion<D>>& motions, double dt, double mu);

}  // namespace sc
