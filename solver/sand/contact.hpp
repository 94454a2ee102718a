// Contact between sand and other particles or walls (the thesis' collision handling, §3.5, after
// the molecular-dynamics model of Bell, Yu & Mucha 2005) and Coulomb friction on rough walls.
#pragma once
#include <algorithm>
#include <cmath>

#include "core/types.hpp"

namespace sc {

/// Spring-dashpot-friction law of a contact (Bell et al. 2005).
struct ContactLaw {
  double stiffness = 0.0;  ///< k_r [N/m]
  double damping = 0.0;    ///< k_d [N s/m], also the tangential viscous coefficient k_t
  double friction = 0.0;   ///< μ [-] of the tangential Coulomb limit
};

/// Largest ω Δt for which symplectic Euler keeps a damped oscillator x'' = −ω² x − 2ζω x' from
/// gaining energy: the step's amplification matrix has det = 1 − 2ζωΔt and trace = 2 − (ωΔt)² −
/// 2ζωΔt, stable while (ωΔt)² + 4ζ ωΔt < 4, i.e. ωΔt < 2(√(1 + ζ²) − ζ) (2 undamped, 1.24 at
/// ζ = 0.5): explicit damping lowers the undamped limit 2.
inline double stable_contact_omega_dt(double zeta) { return 2.0 * (std::sqrt(1.0 + zeta * zeta) - zeta); }

/// The contact law of two particles of masses mi, mj (mj = 0: a wall, infinitely heavy) whose
/// spacing is s: the normal oscillation (of the pair's relative distance, reduced mass m) has the
/// frequency ω = c/s of a sound wave over one spacing and the damping ratio ζ, but at most 0.8 of
/// the explicit stability limit stable_contact_omega_dt(ζ)/Δt of the step Δt. The cap is ours
/// (Bell et al. 2005 leave k_r free): at the thesis' step 0.001 s with c = 20 m/s and s = 0.0093 m,
/// c/s Δt = 2.1 > 1.24, and without the cap a sand grain on the floor gains energy at every bounce
/// (test sand/wall_contact_at_the_thesis_step_only_removes_energy). With a CFL step (c Δt/s ≤ 0.4)
/// the cap never acts.
inline ContactLaw contact_law(double mi, double mj, double s, double sound_speed, double zeta, double mu, double dt) {
  const double m = mj > 0.0 ? mi * mj / (mi + mj) : mi;
  const double omega = std::min(sound_speed / s, 0.8 * stable_contact_omega_dt(zeta) / dt);
  const double k = m * omega * omega;
  return {k, 2.0 * zeta * std::sqrt(k * m), mu};
}

/// Contact force on i from j (Bell et al. 2005): overlap ξ = s − |x_ij| with s the contact distance,
/// normal N = x_ij/|x_ij| (i towards j), normal force f_n = max(0, k_r ξ + k_d ξ̇) pushing i away
/// from j, tangential force −min(μ f_n, k_t |V_t|) V_t/|V_t| against the relative tangential
/// velocity V_t of i. Antisymmetric in i, j (momentum conserved); the damping only dissipates.
/// `d` is x_i − x_j.
template <int D>
Vec<D> contact_force(const ContactLaw& law, const Vec<D>& d, double r, const Vec<D>& vi, const Vec<D>& vj,
                     double contact_distance) {
  const double overlap = contact_distance - r;
  if (overlap <= 0.0 || r <= 0.0) return Vec<D>::Zero();
  const Vec<D> N = -d / r;
  const Vec<D> rel = vi - vj;
  const double approach = rel.dot(N);
  const double fn = std::max(0.0, law.stiffness * overlap + law.damping * approach);
  Vec<D> f = -fn * N;
  const Vec<D> vt = rel - approach * N;
  const double speed = vt.norm();
  if (speed > 0.0) f -= std::min(law.friction * fn, law.damping * speed) * (vt / speed);
  return f;
}

/// Coulomb friction of a rough wall (Zhu & Bridson 2005's frictional wall condition at force level):
/// the wall pushes particle i with `wall_force` (its normal); the tangential part v_t of the velocity
/// the particle would have after the step, v + Δt F/m, is opposed by at most μ |wall_force|, and
/// never by more than stops it within the step (m |v_t|/Δt), so the wall only removes energy.
template <int D>
Vec<D> wall_friction_force(const Vec<D>& wall_force, const Vec<D>& v, const Vec<D>& force, double m, double mu,
                           double dt) {
  const double fn = wall_force.norm();
  if (fn == 0.0) return Vec<D>::Zero();
  const Vec<D> n = wall_force / fn;
  const Vec<D> v_next = v + (dt / m) * force;
  const Vec<D> vt = v_next - v_next.dot(n) * n;
  const double speed = vt.norm();
  if (speed == 0.0) return Vec<D>::Zero();
  return -std::min(mu * fn, m * speed / dt) * (vt / speed);
}

}  // namespace sc
