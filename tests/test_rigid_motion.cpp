// Rigid motion of sand clusters through the solver's own step (cluster_motions, then move_clusters
// with free_turn; solver/sand/clusters.hpp, solver/sand/rigid_body.hpp): torque-free motion
// conserves the angular momentum vector and the kinetic energy while ω precesses (Euler's
// equations; [McLachlan 1993: splitting of the free rigid body], [Dullweber-Leimkuhler-McLachlan
// 1997: symplectic splitting]); the intermediate-axis flip has the period of the exact solution
// (Landau & Lifshitz, Mechanics §37: Jacobi elliptic functions); a constant torque gives
// dL/dt = τ [thesis eq. 12b] [thesis eq. 14] [thesis eq. 16]; the centre of mass of a free body
// keeps its velocity [thesis eq. 13] [thesis eq. 18]; the members keep their distances.
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <numeric>
#include <random>

#include "reference/analytic/free_rigid_body.hpp"
#include "sand/clusters.hpp"

using namespace sc;

namespace {

/// n sand particles of random masses at random points of a box of sides `sides`, all rigid and in
/// one cluster (cluster number 1, as find_clusters writes it).
template <int D>
ParticleSet<D> random_body(int n, const Vec<D>& sides, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.5, 0.5), mass(0.5, 2.0);
  ParticleSet<D> ps;
  for (int k = 0; k < n; ++k) {
    const std::size_t i = ps.append();
    for (int d = 0; d < D; ++d) ps.x[i][d] = sides[d] * u(rng);
    ps.m[i] = mass(rng);
    ps.h[i] = 0.1;
    ps.rho0[i] = ps.rho[i] = 2650.0;
    ps.phase[i] = static_cast<std::uint8_t>(Phase::Sand);
    ps.rigid[i] = 1;
    ps.cluster[i] = 1;
  }
  return ps;
}

template <int D>
Clusters one_cluster(const ParticleSet<D>& ps) {
  std::vector<std::size_t> members(ps.size());
  std::iota(members.begin(), members.end(), 0);
  return Clusters(members);
}

/// Sets the members' velocities to the rigid motion v_cm + ω × (x − r_cm).
template <int D>
void set_rigid_velocity(ParticleSet<D>& ps, const Vec<D>& v_cm, const AngVec<D>& omega) {
  const Clusters one = one_cluster(ps);
  const auto members = one[0];
  const Vec<D> centre = mass_and_centre<D>(members, ps.m, ps.x).second;
  for (const auto i : members) ps.v[i] = v_cm + spin_velocity<D>(omega, ps.x[i] - centre);
}

/// One step of the solver's cluster update with the forces in ps.force (no damping).
template <int D>
void step(ParticleSet<D>& ps, const Clusters& clusters, double dt) {
  move_clusters<D>(ps, clusters, cluster_motions<D>(ps, clusters, dt), dt, 1.0);
}

/// The motion of the members as they are (no force, no step): M, r_cm, P, L, I and ω = I⁻¹L.
template <int D>
ClusterMotion<D> state(const ParticleSet<D>& ps) {
  const Clusters one = one_cluster(ps);
  const auto members = one[0];
  const VecArrayOf<D> no_force(ps.size(), Vec<D>::Zero());
  return rigid_motion<D>(members, ps.m, ps.x, ps.v, no_force, 0.0);
}

/// Rotational kinetic energy ½ L·ω.
template <int D>
double spin_energy(const ClusterMotion<D>& c) {
  return 0.5 * c.angular_momentum.dot(c.omega);
}

/// Largest relative change of a pairwise member distance between two configurations.
template <int D>
double largest_distance_change(const VecArrayOf<D>& a, const VecArrayOf<D>& b) {
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = i + 1; j < a.size(); ++j) {
      const double d0 = (a[i] - a[j]).norm();
      worst = std::max(worst, std::abs((b[i] - b[j]).norm() - d0) / d0);
    }
  return worst;
}

/// The rotation A that carries the offsets from the centre of `start` to those of `now`
/// (least squares; exact for a rigid motion): A = (Σ r rₒᵀ)(Σ rₒ rₒᵀ)⁻¹.
Mat<3> attitude(const ParticleSet<3>& start, const ParticleSet<3>& now) {
  const Clusters one = one_cluster(start);
  const auto members = one[0];
  const Vec<3> c0 = mass_and_centre<3>(members, start.m, start.x).second;
  const Vec<3> c = mass_and_centre<3>(members, now.m, now.x).second;
  Mat<3> cross = Mat<3>::Zero(), gram = Mat<3>::Zero();
  for (const auto i : members) {
    cross += (now.x[i] - c) * (start.x[i] - c0).transpose();
    gram += (start.x[i] - c0) * (start.x[i] - c0).transpose();
  }
  return cross * gram.inverse();
}

/// Torque-free run of the 40-mass body with ω0 = (1, 2, 0.5) rad/s and v_cm = (0.3, −0.1, 0.2) m/s
/// for 1 s at step dt: the largest relative errors of L, energy, v_cm, x_cm, distances, and the
/// largest relative change of ω.
struct FreeRun {
  double L = 0.0, energy = 0.0, velocity = 0.0, centre = 0.0, distances = 0.0, omega_change = 0.0;
};

FreeRun free_run(double dt) {
  ParticleSet<3> ps = random_body<3>(40, Vec<3>(0.4, 0.25, 0.15), 11);
  const Vec<3> v_cm(0.3, -0.1, 0.2);
  set_rigid_velocity<3>(ps, v_cm, Vec<3>(1.0, 2.0, 0.5));
  const Clusters clusters = one_cluster(ps);
  const ClusterMotion<3> s0 = state(ps);
  const VecArrayOf<3> x0 = ps.x;
  const double E0 = spin_energy(s0);
  FreeRun r;
  const int steps = static_cast<int>(std::lround(1.0 / dt));
  for (int n = 1; n <= steps; ++n) {
    step(ps, clusters, dt);
    const ClusterMotion<3> s = state(ps);
    r.L = std::max(r.L, (s.angular_momentum - s0.angular_momentum).norm() / s0.angular_momentum.norm());
    r.energy = std::max(r.energy, std::abs(spin_energy(s) / E0 - 1.0));
    r.velocity = std::max(r.velocity, (s.velocity - v_cm).norm() / v_cm.norm());
    r.centre = std::max(r.centre, (s.centre - s0.centre - n * dt * v_cm).norm() / (n * dt * v_cm.norm()));
    r.omega_change = std::max(r.omega_change, (s.omega - s0.omega).norm() / s0.omega.norm());
  }
  r.distances = largest_distance_change<3>(x0, ps.x);
  return r;
}

/// Over `steps` torque-free steps, the largest gap between a member's displacement in a step and Δt
/// times the mean of its velocities at the two ends, relative to Δt times the body's largest spin
/// speed |v_i − v_cm| at the start.
template <int D>
double largest_displacement_gap(ParticleSet<D> ps, double dt, int steps) {
  const Clusters clusters = one_cluster(ps);
  const Vec<D> v_cm = state(ps).velocity;
  double spin_speed = 0.0;
  for (const auto i : clusters[0]) spin_speed = std::max(spin_speed, (ps.v[i] - v_cm).norm());
  double worst = 0.0;
  for (int n = 0; n < steps; ++n) {
    const VecArrayOf<D> x0 = ps.x, v0 = ps.v;
    step(ps, clusters, dt);
    for (const auto i : clusters[0])
      worst = std::max(worst, ((ps.x[i] - x0[i]) - 0.5 * dt * (v0[i] + ps.v[i])).norm() / (dt * spin_speed));
  }
  return worst;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(rigid_motion)

BOOST_AUTO_TEST_CASE(members_move_the_way_their_velocities_point) {
  // A rigid body's members go where their velocities take them: over a step, a member's displacement
  // is Δt times the mean of its velocities at the two ends (the trapezoidal rule of a smooth motion,
  // here to about (|ω|Δt)² ≈ 1e-5 of the spin's Δt |ω × r|). A body turned against its spin keeps L,
  // the energy and the flip period, but misses this by 2.
  ParticleSet<3> body = random_body<3>(40, Vec<3>(0.4, 0.25, 0.15), 11);
  set_rigid_velocity<3>(body, Vec<3>(0.3, -0.1, 0.2), Vec<3>(1.0, 2.0, 0.5));
  ParticleSet<2> plate = random_body<2>(30, Vec<2>(0.4, 0.2), 9);
  set_rigid_velocity<2>(plate, Vec<2>(0.1, -0.2), AngVec<2>(3.0));
  const double gap3 = largest_displacement_gap<3>(body, 1e-3, 200);
  const double gap2 = largest_displacement_gap<2>(plate, 1e-3, 200);
  BOOST_TEST_MESSAGE("displacement gap 3-D " << gap3 << ", 2-D " << gap2);
  BOOST_TEST(gap3 < 1e-4);
  BOOST_TEST(gap2 < 1e-4);
}

BOOST_AUTO_TEST_CASE(torque_free_3d_body_conserves_L_and_energy_while_omega_precesses) {
  // Euler's equations without torque: L (the vector, in space) and ½ L·ω are constant while
  // ω = I(t)⁻¹L changes. The step conserves L to round-off (every stage of free_turn turns the body
  // at fixed L) and the energy to second order without drift: the error falls 4x when Δt halves.
  // Turning by ωΔt and keeping ω keeps ω to round-off and turns L by about half its size in 1 s.
  const FreeRun coarse = free_run(2e-3), fine = free_run(1e-3);
  BOOST_TEST_MESSAGE("L " << fine.L << " energy " << coarse.energy << " -> " << fine.energy << " omega change "
                          << fine.omega_change);
  BOOST_TEST(fine.L < 1e-10);
  BOOST_TEST(fine.energy < 1e-4);
  BOOST_TEST(coarse.energy / fine.energy > 3.5);  // second order: 4
  BOOST_TEST(coarse.energy / fine.energy < 4.5);
  BOOST_TEST(fine.omega_change > 0.1);  // ω precesses (it is not an eigenvector of I)
}

BOOST_AUTO_TEST_CASE(free_body_keeps_centre_velocity_and_member_distances) {
  // [thesis eq. 13] [thesis eq. 18] corrected: without force P = M v_cm is constant, so the centre
  // moves at v_cm (x_cm = x0 + v_cm t) to round-off; the members turn by rotations about the
  // centre, so every pairwise distance stays to round-off.
  const FreeRun r = free_run(1e-3);
  BOOST_TEST(r.velocity < 1e-13);
  BOOST_TEST(r.centre < 1e-12);
  BOOST_TEST(r.distances < 1e-12);
}

BOOST_AUTO_TEST_CASE(intermediate_axis_flips_with_the_period_of_the_exact_solution) {
  // Dzhanibekov effect: spin close to the intermediate principal axis is unstable; the component of
  // L along that body axis flips sign every half period T/2 of the exact solution of Euler's
  // equations (Landau & Lifshitz §37: analytic::torque_free_period). The step at Δt = 1e-3 s
  // (|ω|Δt = 2e-3) gives the flip interval within 1e-3 of T/2. Turning by ωΔt and keeping ω never
  // flips.
  ParticleSet<3> ps = random_body<3>(40, Vec<3>(0.5, 0.3, 0.15), 7);
  const Clusters clusters = one_cluster(ps);
  {
    const ClusterMotion<3> s = state(ps);
    const Eigen::SelfAdjointEigenSolver<Mat<3>> es(s.inertia);
    const Mat<3> Q = es.eigenvectors();
    set_rigid_velocity<3>(ps, Vec<3>::Zero(), Vec<3>(Q * Vec<3>(0.3, 2.0, 0.2)));
  }
  const ParticleSet<3> start = ps;
  const ClusterMotion<3> s0 = state(ps);
  const Eigen::SelfAdjointEigenSolver<Mat<3>> es(s0.inertia);
  const double I1 = es.eigenvalues()[0], I2 = es.eigenvalues()[1], I3 = es.eigenvalues()[2];
  const Vec<3> axis2 = es.eigenvectors().col(1);
  const Vec<3> w = es.eigenvectors().transpose() * s0.omega;  // in the principal frame
  const double period = analytic::torque_free_period({I1, I2, I3}, {w[0], w[1], w[2]});
  const double dt = 1e-3;
  std::vector<double> flips;
  double previous = s0.angular_momentum.dot(axis2);
  for (int n = 1; n * dt < 2.5 * period; ++n) {
    step(ps, clusters, dt);
    const double along = s0.angular_momentum.dot(attitude(start, ps) * axis2);  // L · (body axis 2)
    if ((along < 0.0) != (previous < 0.0)) flips.push_back((n - 1 + previous / (previous - along)) * dt);
    previous = along;
  }
  BOOST_TEST_MESSAGE("period " << period << " s, flips " << flips.size());
  BOOST_TEST_REQUIRE(flips.size() >= 4u);
  const double half = (flips.back() - flips.front()) / static_cast<double>(flips.size() - 1);
  BOOST_TEST_MESSAGE("flip interval / (T/2) - 1 = " << half / (0.5 * period) - 1.0);
  BOOST_TEST(std::abs(half / (0.5 * period) - 1.0) < 1e-3);
}

BOOST_AUTO_TEST_CASE(constant_torque_gives_dL_dt_equal_to_torque) {
  // [thesis eq. 12b] [thesis eq. 14] [thesis eq. 16]: member forces F_i = m_i β × r'_i with
  // β = I⁻¹τ add up to zero force and the torque Σ r'_i × F_i = Iβ = τ; set every step for the
  // body as it has turned, they make L(t) = L0 + τ t to round-off while P stays.
  ParticleSet<3> ps = random_body<3>(40, Vec<3>(0.4, 0.25, 0.15), 3);
  const Vec<3> v_cm(0.0, 0.2, -0.1);
  set_rigid_velocity<3>(ps, v_cm, Vec<3>(0.5, -1.0, 1.5));
  const Clusters clusters = one_cluster(ps);
  const ClusterMotion<3> s0 = state(ps);
  const Vec<3> tau(0.02, 0.05, -0.03);  // [N m]
  const double dt = 1e-3;
  double L_error = 0.0, P_error = 0.0;
  for (int n = 1; n <= 1000; ++n) {
    const ClusterMotion<3> s = state(ps);
    const Vec<3> beta = solve_inertia<3>(s.inertia, tau);
    for (const auto i : clusters[0]) ps.force[i] = ps.m[i] * beta.cross(ps.x[i] - s.centre);
    step(ps, clusters, dt);
    const ClusterMotion<3> after = state(ps);
    const Vec<3> L_exact = s0.angular_momentum + n * dt * tau;
    L_error = std::max(L_error, (after.angular_momentum - L_exact).norm() / L_exact.norm());
    P_error = std::max(P_error, (after.momentum - s0.momentum).norm() / s0.momentum.norm());
  }
  BOOST_TEST_MESSAGE("L error " << L_error << ", P error " << P_error);
  BOOST_TEST(L_error < 1e-10);
  BOOST_TEST(P_error < 1e-12);
}

BOOST_AUTO_TEST_CASE(uniform_load_moves_the_centre_as_a_free_particle) {
  // [thesis eq. 13] [thesis eq. 18]: member forces F_i = m_i a (a uniform load, no torque about the
  // centre) on a spinning body make P_n = P_0 + n Δt M a, and the centre follows the particles'
  // symplectic Euler recurrence, x_n = x_0 + n Δt v_0 + a Δt² n(n + 1)/2, while L stays; to
  // round-off over 300 steps.
  ParticleSet<3> ps = random_body<3>(40, Vec<3>(0.4, 0.25, 0.15), 13);
  const Vec<3> v_cm(0.3, -0.1, 0.2), a(1.5, -0.5, -9.81);
  set_rigid_velocity<3>(ps, v_cm, Vec<3>(1.0, -0.5, 2.0));
  const Clusters clusters = one_cluster(ps);
  const ClusterMotion<3> s0 = state(ps);
  const double dt = 1e-3;
  const int n = 300;
  for (int k = 0; k < n; ++k) {
    for (const auto i : clusters[0]) ps.force[i] = ps.m[i] * a;
    step(ps, clusters, dt);
  }
  const ClusterMotion<3> s = state(ps);
  const Vec<3> P_exact = s0.momentum + (n * dt * s0.mass) * a;
  const Vec<3> x_exact = s0.centre + (n * dt) * v_cm + (dt * dt * n * (n + 1) / 2.0) * a;
  BOOST_TEST((s.momentum - P_exact).norm() <= 1e-12 * P_exact.norm());
  BOOST_TEST((s.centre - x_exact).norm() <= 1e-12 * x_exact.norm());
  BOOST_TEST((s.angular_momentum - s0.angular_momentum).norm() <= 1e-10 * s0.angular_momentum.norm());
}

BOOST_AUTO_TEST_CASE(body_on_a_line_turns_about_its_perpendicular_axes_only) {
  // Members on a line have no moment about it (solve_inertia's pseudo-inverse): a symmetric top
  // whose ω ⊥ line stays; free_turn turns it by ωΔt: finite, L kept to round-off, distances kept.
  ParticleSet<3> ps = random_body<3>(6, Vec<3>(1.0, 0.0, 0.0), 5);
  set_rigid_velocity<3>(ps, Vec<3>::Zero(), Vec<3>(0.0, 1.0, 2.0));
  const Clusters clusters = one_cluster(ps);
  const ClusterMotion<3> s0 = state(ps);
  const VecArrayOf<3> x0 = ps.x;
  for (int n = 0; n < 1000; ++n) step(ps, clusters, 1e-3);
  const ClusterMotion<3> s = state(ps);
  BOOST_TEST(s.omega.allFinite());
  BOOST_TEST((s.angular_momentum - s0.angular_momentum).norm() < 1e-12 * s0.angular_momentum.norm());
  BOOST_TEST(largest_distance_change<3>(x0, ps.x) < 1e-12);
  BOOST_TEST(s0.omega.norm() > 1.0);
}

BOOST_AUTO_TEST_CASE(planar_body_keeps_its_spin) {
  // 2-D: ω is a scalar about the normal and I does not change as the body turns, so ω, L and the
  // energy stay to round-off and the body turns by ωt.
  ParticleSet<2> ps = random_body<2>(30, Vec<2>(0.4, 0.2), 9);
  set_rigid_velocity<2>(ps, Vec<2>(0.1, -0.2), AngVec<2>(3.0));
  const Clusters clusters = one_cluster(ps);
  const ClusterMotion<2> s0 = state(ps);
  const std::size_t far = 0;
  const Vec<2> r0 = ps.x[far] - s0.centre;
  const double dt = 1e-3;
  for (int n = 0; n < 1000; ++n) step(ps, clusters, dt);
  const ClusterMotion<2> s = state(ps);
  BOOST_TEST(std::abs(s.omega[0] - 3.0) < 1e-12);
  BOOST_TEST(std::abs(s.angular_momentum[0] / s0.angular_momentum[0] - 1.0) < 1e-12);
  BOOST_TEST(((ps.x[far] - s.centre) - rotation<2>(AngVec<2>(3.0)) * r0).norm() < 1e-12 * r0.norm());
}

BOOST_AUTO_TEST_CASE(start_up_damping_scales_the_members_velocities_and_not_their_step) {
  // The start-up relaxation scales every moving particle's new velocity by the factor d
  // (symplectic_euler_step: v ← d (v + Δt F/m)); move_clusters does the same to a rigid cluster,
  // v_i ← d (v_cm + ω' × (x_i − r_cm')), with the positions of the undamped step. One step of a
  // spinning 40-mass body under gravity with d = 0.5 (a power of two, so the scaling is exact) gives
  // exactly half the member velocities of d = 1, at the same positions.
  ParticleSet<3> ps = random_body<3>(40, Vec<3>(0.4, 0.25, 0.15), 19);
  set_rigid_velocity<3>(ps, Vec<3>(0.3, -0.1, 0.2), Vec<3>(1.0, 2.0, 0.5));
  for (std::size_t i = 0; i < ps.size(); ++i) ps.force[i] = ps.m[i] * Vec<3>(0.0, 0.0, -9.81);
  const Clusters clusters = one_cluster(ps);
  const double dt = 1e-3;
  const std::vector<ClusterMotion<3>> motions = cluster_motions<3>(ps, clusters, dt);
  BOOST_TEST_REQUIRE(motions[0].velocity.norm() > 0.3);
  ParticleSet<3> undamped = ps, damped = ps;
  move_clusters<3>(undamped, clusters, motions, dt, 1.0);
  move_clusters<3>(damped, clusters, motions, dt, 0.5);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    BOOST_TEST((damped.v[i] - 0.5 * undamped.v[i]).norm() == 0.0);
    BOOST_TEST((damped.x[i] - undamped.x[i]).norm() == 0.0);
  }
}

BOOST_AUTO_TEST_CASE(a_cluster_of_many_chunks_has_the_motion_of_all_its_members) {
  // cluster_motions sums a large cluster's members by chunks (of 512, in parallel) and adds the
  // chunks' sums: M, r_cm, P, L, I (eqs 13-17), v_cm = P/M and ω = I⁻¹L must be those of
  // rigid_motion, which sums every member in one pass. A 1300-member body (three chunks) of random
  // masses, spinning, under gravity and random member forces, one step of 1 ms: equal to round-off
  // (1e-12 relative; the centre within 1e-12 of the body's length).
  ParticleSet<3> ps = random_body<3>(1300, Vec<3>(0.4, 0.25, 0.15), 23);
  set_rigid_velocity<3>(ps, Vec<3>(0.3, -0.1, 0.2), Vec<3>(1.0, 2.0, 0.5));
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const Vec<3> push(u(rng), u(rng), u(rng));
    ps.force[i] = ps.m[i] * Vec<3>(0.0, 0.0, -9.81) + push;
  }
  const Clusters clusters = one_cluster(ps);
  const double dt = 1e-3;
  const ClusterMotion<3> chunked = cluster_motions<3>(ps, clusters, dt)[0];
  const ClusterMotion<3> whole = sc::rigid_motion<3>(clusters[0], ps.m, ps.x, ps.v, ps.force, dt);
  const auto rel = [](const auto& a, const auto& b) { return (a - b).norm() / b.norm(); };
  BOOST_TEST(chunked.mass == whole.mass, boost::test_tools::tolerance(1e-13));
  BOOST_TEST((chunked.centre - whole.centre).norm() <= 1e-12 * 0.4);
  BOOST_TEST(rel(chunked.momentum, whole.momentum) <= 1e-12);
  BOOST_TEST(rel(chunked.angular_momentum, whole.angular_momentum) <= 1e-12);
  BOOST_TEST(rel(chunked.inertia, whole.inertia) <= 1e-12);
  BOOST_TEST(rel(chunked.velocity, whole.velocity) <= 1e-12);
  BOOST_TEST(rel(chunked.omega, whole.omega) <= 1e-12);
}

BOOST_AUTO_TEST_SUITE_END()
