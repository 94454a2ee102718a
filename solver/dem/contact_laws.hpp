// Contact and bridge laws between two grains (or a grain and a wall), after Rungjiratananon et al.
// 2008 (seed 003) with the seed's bugs fixed openly:
// - the spring acts along the contact normal (the seed directs it along the normal relative
//   velocity, which flips sign as the grains separate);
// - the tangential force is a Coulomb law regularised by a tangential spring with contact history
//   (Cundall & Strack 1979), bounded by μ|F_n| (the seed's constant-magnitude form chatters, and a
//   purely viscous regularisation creeps under a static load, so no pile could stand);
// - the bridge acts only between two grains that both hold water (the seed's form gives two dry
//   grains the strongest bridge).
// Every law returns the force on grain i; evaluated from j's side, with j's springs (the exact
// negatives of i's), it gives the exact negative (the pair terms are antisymmetric in their inputs),
// so momentum is conserved. The torque on j is returned beside i's, as j's own evaluation gives it, so
// a pair is evaluated once for both grains (solver/dem/dem_forces.cpp).
#pragma once
#include <algorithm>
#include <cmath>

#include "dem/grains.hpp"

namespace sc::dem {

/// One contact seen from grain i: n points from i to the other body.
template <int D>
struct Contact {
  Vec<D> n;              ///< unit normal from i towards j
  double overlap;        ///< a_i + a_j − |x_j − x_i| > 0 [m]
  Vec<D> v_contact;      ///< velocity of i's contact point relative to j's [m/s]
  Spin<D> omega_rel;     ///< ω_i − ω_j [rad/s]
  double wet_factor;     ///< 1 + w_i + w_j
  double friction;       ///< μ of the pair
  double r_eff;          ///< a_i a_j/(a_i + a_j) (a_i for a wall) [m]
  double lever;          ///< a_i: distance from i's centre to the contact point [m]
  double lever_other;    ///< a_j: distance from j's centre to the contact point (0 for a wall) [m]
};

template <int D>
struct ContactForce {
  Vec<D> force;          ///< on i [N]
  Spin<D> torque;        ///< on i about its centre [N m]
  Spin<D> torque_other = Spin<D>::Zero();  ///< on j about its centre, the bits of j's own evaluation [N m]
  bool touching = false; ///< the bodies overlap: the contact's springs are kept for the next step
};

/// Normal force magnitude (positive = repulsive) of the linear spring-dashpot, spring along the
/// contact normal and dashpot raised by wetness [Rungjiratananon 2008: DEM normal force]:
///   F_n = k_s δ + k_d (1 + w_i + w_j) v_n,   v_n = (v_i − v_j)·n (approach speed).
/// No tensile clamp: the contact ends when δ returns to zero, so restitution and contact time are
/// those of the damped oscillator (tests/test_dem.cpp pins both).
inline double normal_force(double k_s, double k_d, double wet_factor, double overlap, double v_n) {
  return k_s * overlap + k_d * wet_factor * v_n;
}

/// Coulomb friction with a tangential spring [Cundall & Strack 1979; Rungjiratananon 2008: DEM
/// tangential force, fixed]: the stretch ξ, kept in the tangent plane, grows by v_t Δt; the force
/// −k_t ξ − γ_t (1 + w_i + w_j) v_t is bounded by μ|F_n|, and at the bound (sliding) ξ is reset to
/// the stretch that gives the bounded force. A stuck contact holds any tangential load below μ|F_n|.
template <int D>
inline Vec<D> tangential_force(const Vec<D>& n, const Vec<D>& v_t, double k_t, double gamma_t, double wet_factor,
                               double mu, double f_n, double dt, Vec<D>& slip) {
  slip -= slip.dot(n) * n;
  slip += dt * v_t;
  const Vec<D> f = -k_t * slip - (gamma_t * wet_factor) * v_t;
  const double bound = mu * std::abs(f_n), magnitude = f.norm();
  if (magnitude <= bound) return f;
  const Vec<D> sliding = (bound / magnitude) * f;
  slip = (-1.0 / k_t) * (sliding + (gamma_t * wet_factor) * v_t);
  return sliding;
}

/// Rolling resistance, elastic-plastic spring-dashpot (ours, not in the paper: piles of round grains
/// need it to stand near 30°) [Ai et al. 2011: rolling model C]: the twist ψ grows by (ω_i − ω_j) Δt;
/// the torque −k_r ψ − γ_r (ω_i − ω_j), k_r = 2.25 k_n μ_r² R_eff², is bounded by μ_r R_eff |F_n|,
/// and at the bound ψ is reset to the twist that gives the bounded torque.
template <int D>
inline Spin<D> rolling_torque(const Spin<D>& omega_rel, double k_n, double gamma_r, double mu_r, double r_eff,
                              double f_n, double dt, Spin<D>& roll) {
  if (mu_r <= 0.0) return Spin<D>::Zero();
  const double k_r = 2.25 * k_n * mu_r * mu_r * r_eff * r_eff;
  roll += dt * omega_rel;
  const Spin<D> m = -k_r * roll - gamma_r * omega_rel;
  const double bound = mu_r * r_eff * std::abs(f_n), magnitude = m.norm();
  if (magnitude <= bound) return m;
  const Spin<D> rolling = (bound / magnitude) * m;
  roll = (-1.0 / k_r) * (rolling + gamma_r * omega_rel);
  return rolling;
}

/// Spring-dashpot, friction and rolling resistance of one contact over a step Δt, on grain i (and the
/// torque on j); the contact's springs are read and advanced in `spring`. From j's side the normal,
/// tangential force and rolling torque are the exact negatives of i's, so j's torque is
/// a_j n × f_t − m_r with i's n, f_t and m_r: the same bits as j's own a_j (−n) × (−f_t) + (−m_r).
template <int D>
ContactForce<D> contact_force(const Contact<D>& c, const Params& p, double dt, Spring<D>& spring) {
  const double v_n = c.v_contact.dot(c.n);
  const double f_n = normal_force(p.stiffness, p.damping, c.wet_factor, c.overlap, v_n);
  const Vec<D> v_t = c.v_contact - v_n * c.n;
  const Vec<D> f_t = tangential_force<D>(c.n, v_t, p.tangential_stiffness_ratio * p.stiffness, p.tangential_damping,
                                         c.wet_factor, c.friction, f_n, dt, spring.slip);
  ContactForce<D> out{-f_n * c.n + f_t, Spin<D>::Zero(), Spin<D>::Zero(), true};
  if (p.rotation) {
    const Spin<D> rolling = rolling_torque<D>(c.omega_rel, p.stiffness, p.rolling_damping, p.rolling_friction,
                                              c.r_eff, f_n, dt, spring.roll);
    out.torque = moment<D>(c.lever * c.n, f_t) + rolling;
    out.torque_other = moment<D>(c.lever_other * c.n, f_t) - rolling;
  }
  return out;
}

/// The paper's liquid bridge, on grain i [Rungjiratananon 2008: liquid bridge, fixed]:
///   F_i = k_bridge max(0, w_f − (w_i + w_j)/2) (v_j − v_i)   while (v_j − v_i)·(x_j − x_i) > 0,
/// zero unless both grains hold water. A velocity-proportional glue: it resists separation only.
template <int D>
inline Vec<D> paper_bridge_force(double k_bridge, double w_f, double w_i, double w_j, const Vec<D>& v_ji,
                                 const Vec<D>& x_ji) {
  if (!(w_i > 0.0 && w_j > 0.0) || v_ji.dot(x_ji) <= 0.0) return Vec<D>::Zero();
  return (k_bridge * std::max(0.0, w_f - 0.5 * (w_i + w_j))) * v_ji;
}

/// Rupture distance of a bridge of volume V (Lian 1993): S_c = (1 + θ/2) V^{1/3}.
inline double rupture_distance(double volume, double theta) { return (1.0 + 0.5 * theta) * std::cbrt(volume); }

/// Capillary force magnitude (attractive) of a pendular bridge of volume V between spheres of
/// effective radius R at gap S [Willett 2000: eq. 12-13]:
///   F = 2πRγ cos θ / (1 + 2.1 s⁺ + 10 s⁺²),  s⁺ = (S/2)√(R/V);  F = 2πRγ cos θ in contact (S <= 0),
/// zero beyond the rupture distance.
inline double willett_force(double r_eff, double gap, double volume, double gamma, double theta) {
  const double f0 = 2.0 * pi * r_eff * gamma * std::cos(theta);
  if (gap <= 0.0) return f0;
  if (gap > rupture_distance(volume, theta)) return 0.0;
  const double s = 0.5 * gap * std::sqrt(r_eff / volume);
  return f0 / (1.0 + 2.1 * s + 10.0 * s * s);
}

/// Pull-off force of one coarse-grained bridge, for grains of diameter d that stand for the sand of
/// a site and must give the packing the bulk cohesion c of a case [Rumpf: tensile strength of a
/// bridged packing, σ_t = ((1 − ε)/ε) F/d^{D−1}; ours: c = σ_t tan φ (docs/equations.md §7.8)]:
///   F0 = c ε d^{D−1} / ((1 − ε) tan φ)   (per metre of depth in 2-D).
inline double bridge_pull_off(double c, double tan_phi, double porosity, double d, int dim) {
  return c * porosity * std::pow(d, dim - 1) / ((1.0 - porosity) * tan_phi);
}

}  // namespace sc::dem
