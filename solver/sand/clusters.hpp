// Clusters of non-yielding sand and their rigid motion (thesis §3.3, Fig. 3.2; Zhu & Bridson 2005's
// "rigid groups"; Baraff 2001).
#pragma once
#include <vector>

#include "core/particle_set.hpp"
#include "neighbours/neighbour_grid.hpp"
#include "sand/rigid_body.hpp"

namespace sc {

using Clusters = std::vector<std::vector<std::size_t>>;

/// Groups the rigid sand particles (ps.rigid) into clusters: two rigid particles belong to the same
/// cluster when they are neighbours (|x_ij| ≤ max(h_i, h_j), the thesis' h' ≤ h). Breadth-first
/// search; seeds in increasing index order and neighbours in list order, so the clusters and the
/// order of their members do not depend on the number of threads. Writes ps.cluster (number + 1,
/// 0 for particles in no cluster).
template <int D>
Clusters find_clusters(ParticleSet<D>& ps, const NeighbourGrid<D>& nb);

/// Rigid motion of every cluster for a step dt (rigid_motion: eqs 13-18) from the velocities and
/// forces at the start of the step, with the inertia tensor of eq 17 in the given form.
template <int D>
std::vector<ClusterMotion<D>> cluster_motions(const ParticleSet<D>& ps, const Clusters& clusters, double dt,
                                              InertiaForm form = InertiaForm::Corrected);

/// Moves the members of every cluster rigidly by one step: x ← r_cm + Δt v_cm + R (x − r_cm), then
/// v ← damping (v_cm + ω' × (x − r_cm_new)), eq 18 in its corrected form, with R and ω' the
/// torque-free turn of the cluster (free_turn: L = Iω is carried through the step, so in 3-D ω
/// precesses and L stays). The members are found by ps.cluster (as find_clusters writes it).
template <int D>
void move_clusters(ParticleSet<D>& ps, const Clusters& clusters, const std::vector<ClusterMotion<D>>& motions,
                   double dt, double damping);

}  // namespace sc
