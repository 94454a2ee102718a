// Rigid-body quantities of a cluster of particles (Baraff 2001), in 2-D and 3-D.
//
// Angular quantities live in AngVec<D>/AngMat<D>: 3-vectors and 3x3 matrices in 3-D, 1-vectors and
// 1x1 matrices (the z component) in 2-D, where rotations are about the normal of the plane.
#pragma once
#include <span>
#include <tuple>
#include <vector>

#include "core/types.hpp"
#include "sand/sand_params.hpp"

namespace sc {

template <int D>
inline constexpr int angular_dim = D == 2 ? 1 : 3;
template <int D>
using AngVec = Eigen::Matrix<double, angular_dim<D>, 1>;
template <int D>
using AngMat = Eigen::Matrix<double, angular_dim<D>, angular_dim<D>>;
template <int D>
using VecArrayOf = std::vector<Vec<D>, Eigen::aligned_allocator<Vec<D>>>;

/// The moment r × f (in 2-D the scalar r_x f_y − r_y f_x).
template <int D>
inline AngVec<D> moment(const Vec<D>& r, const Vec<D>& f) {
  if constexpr (D == 3) return r.cross(f);
  else return AngVec<2>(r[0] * f[1] - r[1] * f[0]);
}

/// The velocity ω × r of a point at r from the axis (in 2-D ω is the scalar about z).
template <int D>
inline Vec<D> spin_velocity(const AngVec<D>& omega, const Vec<D>& r) {
  if constexpr (D == 3) return omega.cross(r);
  else return Vec<2>(-omega[0] * r[1], omega[0] * r[0]);
}

/// Torque of one particle about the centre of mass [thesis eq. 12b] (Baraff 2001):
/// τ_i = (r_i − r_cm) × F_i. Correct; only the equation number (12) is used twice in the thesis.
template <int D>
inline AngVec<D> torque(const Vec<D>& x, const Vec<D>& centre, const Vec<D>& force) {
  return moment<D>(x - centre, force);
}

/// Mass, centre of mass, momentum and angular momentum (about the centre), and inertia of a cluster.
template <int D>
struct ClusterMotion {
  double mass = 0.0;
  Vec<D> centre = Vec<D>::Zero();
  Vec<D> momentum = Vec<D>::Zero();
  AngVec<D> angular_momentum = AngVec<D>::Zero();
  AngMat<D> inertia = AngMat<D>::Zero();
  Vec<D> velocity = Vec<D>::Zero();        ///< v_cm = P/M
  AngVec<D> omega = AngVec<D>::Zero();     ///< ω = I⁻¹ L
};

/// Total mass and first mass moment Σ m x of the members.
template <int D>
std::pair<double, Vec<D>> mass_and_moment(std::span<const std::size_t> members, std::span<const double> m,
                                          const VecArrayOf<D>& x) {
  double M = 0.0;
  Vec<D> s = Vec<D>::Zero();
  for (const auto i : members) {
    M += m[i];
    s += m[i] * x[i];
  }
  return {M, s};
}

/// Total mass and centre of mass of the members.
template <int D>
std::pair<double, Vec<D>> mass_and_centre(std::span<const std::size_t> members, std::span<const double> m,
                                          const VecArrayOf<D>& x) {
  const auto [M, s] = mass_and_moment<D>(members, m, x);
  return {M, s / M};
}

/// Cluster force [thesis eq. 13]: F_cluster = Σ_{i ∈ cluster} F_i. Correct as printed.
template <int D>
Vec<D> cluster_force(std::span<const std::size_t> members, const VecArrayOf<D>& force) {
  Vec<D> F = Vec<D>::Zero();
  for (const auto i : members) F += force[i];
  return F;
}

/// Cluster torque [thesis eq. 14]: τ_cluster = Σ_{i ∈ cluster} τ_i, τ_i of eq 12b. Correct.
template <int D>
AngVec<D> cluster_torque(std::span<const std::size_t> members, const VecArrayOf<D>& x, const Vec<D>& centre,
                         const VecArrayOf<D>& force) {
  AngVec<D> tau = AngVec<D>::Zero();
  for (const auto i : members) tau += torque<D>(x[i], centre, force[i]);
  return tau;
}

/// Inertia tensor about the centre [thesis eq. 17] (Baraff 2001): I = Σ m_j (|r'_j|² 𝟙 − r'_j r'_jᵀ),
/// r'_j = r_j − r_cm; in 2-D the single entry I_zz = Σ m_j |r'_j|². Erratum 17: the thesis prints
/// the second diagonal entry as m(r'_y² + r'_z²); it is m(r'_x² + r'_z²). The identity/outer-product
/// form used by default cannot carry that typo; InertiaForm::Printed puts it back (3-D), so the
/// errata-impact table can show what it does (sand.inertia_tensor = "printed").
template <int D>
AngMat<D> inertia_tensor(std::span<const std::size_t> members, std::span<const double> m, const VecArrayOf<D>& x,
                         const Vec<D>& centre, InertiaForm form = InertiaForm::Corrected) {
  AngMat<D> I = AngMat<D>::Zero();
  for (const auto j : members) {
    const Vec<D> r = x[j] - centre;
    if constexpr (D == 3) {
      I += m[j] * (r.squaredNorm() * Mat<3>::Identity() - r * r.transpose());
      if (form == InertiaForm::Printed) I(1, 1) += m[j] * (r.y() * r.y() - r.x() * r.x());  // y² in place of x²
    } else {
      I(0, 0) += m[j] * r.squaredNorm();
    }
  }
  return I;
}

/// Solves I a = b for a, the way [thesis eq. 15] τ = Iα is inverted in [thesis eq. 16] α = I⁻¹τ
/// (and ω = I⁻¹L). A singular or near-singular I (one particle, or particles on a line) is inverted
/// on its range only (Moore-Penrose pseudo-inverse, eigenvalues below `rel_tol` times the largest
/// count as zero), so such clusters cannot spin about the degenerate axis.
template <int D>
AngVec<D> solve_inertia(const AngMat<D>& I, const AngVec<D>& b, double rel_tol = 1e-10) {
  Eigen::SelfAdjointEigenSolver<AngMat<D>> es(I);
  const auto& lambda = es.eigenvalues();
  const double largest = lambda.cwiseAbs().maxCoeff();
  AngVec<D> coeffs = es.eigenvectors().transpose() * b;
  for (int k = 0; k < angular_dim<D>; ++k) coeffs[k] = lambda[k] > rel_tol * largest && largest > 0.0 ? coeffs[k] / lambda[k] : 0.0;
  return es.eigenvectors() * coeffs;
}

/// The sums over the members of a cluster (or a part of one) about the centre r_cm that its rigid
/// motion needs: Σ m_j v_j, Σ m_j r'_j × v_j, F_cluster [thesis eq. 13], τ_cluster [thesis eq. 14]
/// and I [thesis eq. 17]; the sums of disjoint parts add up.
template <int D>
struct MotionSums {
  Vec<D> momentum = Vec<D>::Zero();
  AngVec<D> angular_momentum = AngVec<D>::Zero();
  Vec<D> force = Vec<D>::Zero();
  AngVec<D> torque = AngVec<D>::Zero();
  AngMat<D> inertia = AngMat<D>::Zero();

  MotionSums& operator+=(const MotionSums& o) {
    momentum += o.momentum;
    angular_momentum += o.angular_momentum;
    force += o.force;
    torque += o.torque;
    inertia += o.inertia;
    return *this;
  }
};

/// MotionSums of the members about `centre` (the inertia in the given form of eq 17).
template <int D>
MotionSums<D> motion_sums(std::span<const std::size_t> members, std::span<const double> m, const VecArrayOf<D>& x,
                          const VecArrayOf<D>& v, const VecArrayOf<D>& force, const Vec<D>& centre,
                          InertiaForm form = InertiaForm::Corrected) {
  MotionSums<D> s;
  for (const auto j : members) {
    s.momentum += m[j] * v[j];
    s.angular_momentum += moment<D>(x[j] - centre, m[j] * v[j]);
  }
  s.force = cluster_force<D>(members, force);
  s.torque = cluster_torque<D>(members, x, centre, force);
  s.inertia = inertia_tensor<D>(members, m, x, centre, form);
  return s;
}

/// Rigid motion of a cluster after one step [thesis eq. 15], [thesis eq. 16], [thesis eq. 18]
/// (corrected form, docs/equations.md eqs 15-18), from its mass M, centre and motion_sums:
///   P = Σ m_j v_j + F_cluster Δt,  L = Σ m_j r'_j × v_j + τ_cluster Δt,  v_cm = P/M,  ω = I⁻¹ L,
/// from the velocities and forces at the start of the step. Errata: eqs 15-16 drop the gyroscopic
/// term ω × Iω and the time dependence of I; updating L (not ω) here, and turning the body at that L
/// with free_turn (which gives ω at the end of the step), keeps them (angular momentum is conserved
/// to round-off when τ = 0). Eq 18 divides the cluster force by the particle mass m_i
/// (N_cluster times too large; it must be the cluster mass M) and adds increments to each particle's
/// old velocity, which never makes a new cluster rigid; here every member gets v_cm + ω × r'
/// (move_clusters). The cross-product order (α Δt) × r' of the thesis is right.
/// `spins`: false for one particle, whose I and L are round-off about its own centre.
template <int D>
ClusterMotion<D> motion_from_sums(double mass, const Vec<D>& centre, const MotionSums<D>& s, double dt, bool spins) {
  ClusterMotion<D> c;
  c.mass = mass;
  c.centre = centre;
  c.momentum = s.momentum + dt * s.force;
  c.angular_momentum = s.angular_momentum + dt * s.torque;
  c.inertia = s.inertia;
  c.velocity = c.momentum / c.mass;
  if (spins) c.omega = solve_inertia<D>(c.inertia, c.angular_momentum);
  return c;
}

/// motion_from_sums of the members [thesis eq. 15], [thesis eq. 16], [thesis eq. 18].
template <int D>
ClusterMotion<D> rigid_motion(std::span<const std::size_t> members, std::span<const double> m,
                              const VecArrayOf<D>& x, const VecArrayOf<D>& v, const VecArrayOf<D>& force, double dt) {
  const auto [mass, centre] = mass_and_centre<D>(members, m, x);
  return motion_from_sums<D>(mass, centre, motion_sums<D>(members, m, x, v, force, centre), dt, members.size() > 1);
}

/// Velocity of a member at x in the rigid motion c: v_cm + ω × (x − r_cm) [thesis eq. 18], corrected.
template <int D>
inline Vec<D> rigid_velocity(const ClusterMotion<D>& c, const Vec<D>& x) {
  return c.velocity + spin_velocity<D>(c.omega, x - c.centre);
}

/// Rotation matrix of the rotation by the angle vector ω Δt (Rodrigues' formula in 3-D).
template <int D>
Mat<D> rotation(const AngVec<D>& angle) {
  if constexpr (D == 2) {
    const double c = std::cos(angle[0]), s = std::sin(angle[0]);
    return (Mat<2>() << c, -s, s, c).finished();
  } else {
    const double theta = angle.norm();
    if (theta == 0.0) return Mat<3>::Identity();
    return Eigen::AngleAxisd(theta, angle / theta).toRotationMatrix();
  }
}

/// The turn of a rigid body over one step and its angular velocity at the end of the step.
template <int D>
struct Turn {
  Mat<D> rotation = Mat<D>::Identity();  ///< R: an offset r' from the centre becomes R r'
  AngVec<D> omega = AngVec<D>::Zero();   ///< ω at the end of the step: I(t + Δt)⁻¹ L
};

/// Torque-free turn over Δt of a rigid body of inertia I about its centre [thesis eq. 17] that spins
/// at ω at the start of the step; its angular momentum L = Iω is conserved (rigid clusters after
/// Zhu-Bridson 2005, whose rigid groups keep the momenta of their members).
/// In 2-D ω is a scalar about the normal of the plane and does not change: R = R(ωΔt).
/// In 3-D [McLachlan 1993: splitting of the free rigid body], in the symmetric form of
/// [Dullweber-Leimkuhler-McLachlan 1997: symplectic splitting]: the kinetic energy
/// T = Σ_k (L·e_k)²/(2 I_k) over the principal axes e_k (moments I_k) is split into its three terms.
/// The flow of one term is exact: the body turns about e_k by the angle t (L·e_k)/I_k (e_k and L
/// stay, the other axes turn). The step composes them symmetrically, T_a(Δt/2) T_b(Δt/2) T_c(Δt)
/// T_b(Δt/2) T_a(Δt/2), with a the largest moment and c the smallest. Every stage is a rotation at
/// fixed L, so L (the vector) is conserved to round-off and ω = I(t)⁻¹L precesses by Euler's
/// equations; the composition is symplectic, time-reversible and of second order, so the kinetic
/// energy ½ L·ω is conserved to O((|ω|Δt)²) without drift. Rotating by ωΔt and keeping ω (the
/// form that drops the gyroscopic term ω × Iω) keeps ω but turns L (tests/test_rigid_motion.cpp).
/// A body whose smallest moment is below rel_tol times the largest lies on a line (solve_inertia
/// gives it no spin about the line): it is a symmetric top with ω ⊥ line, ω stays, and R(ωΔt) is exact.
template <int D>
Turn<D> free_turn(const AngMat<D>& inertia, const AngVec<D>& omega, double dt, double rel_tol = 1e-10) {
  if constexpr (D == 2) {
    return {rotation<2>(dt * omega), omega};
  } else {
    const Eigen::SelfAdjointEigenSolver<Mat<3>> es(inertia);
    const Vec<3>& moments = es.eigenvalues();  // increasing
    const double largest = moments.cwiseAbs().maxCoeff();
    if (!(moments[0] > rel_tol * largest)) return {rotation<3>(dt * omega), omega};
    const Vec<3> L = inertia * omega;
    Mat<3> axes = es.eigenvectors();  // columns: the principal axes, turned with the body
    Turn<3> turn;
    auto stage = [&](int k, double h) {
      const Mat<3> S = rotation<3>(Vec<3>((h * L.dot(axes.col(k)) / moments[k]) * axes.col(k)));
      axes = S * axes;
      turn.rotation = S * turn.rotation;
    };
    stage(2, 0.5 * dt);
    stage(1, 0.5 * dt);
    stage(0, dt);
    stage(1, 0.5 * dt);
    stage(2, 0.5 * dt);
    for (int k = 0; k < 3; ++k) turn.omega += (L.dot(axes.col(k)) / moments[k]) * axes.col(k);
    return turn;
  }
}

/// Position of a member after a step of the rigid motion: the centre moves with v_cm, the offset
/// r' turns by R(ω Δt) (no radial drift, unlike x += Δt (ω × r')).
template <int D>
inline Vec<D> rigid_position(const ClusterMotion<D>& c, const Mat<D>& R, const Vec<D>& x, double dt) {
  return c.centre + dt * c.velocity + R * (x - c.centre);
}

}  // namespace sc
