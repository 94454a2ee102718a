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

/// The contact law of two particles of masses mi, mj (mj = 0: a wall, infinitely heavy) whose
/// spacing is s: the normal oscillation has the frequency c/s of a sound wave over one spacing and
/// the damping ratio ζ.
inline ContactLaw contact_law(double mi, double mj, double s, double sound_speed, double zeta, double mu) {
  const double m = mj > 0.0 ? mi * mj / (mi + mj) : mi;
  const double k = m * (sound_speed / s) * (sound_speed / s);
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
