// Cohesion-based surface tension (Becker & Teschner 2007), in a form symmetric for unequal masses.
#pragma once
#include "sph/kernels.hpp"

namespace sc {

/// Surface-tension (cohesion) force on i from j, after Becker & Teschner 2007,
/// a_i = −(κ/m_i) Σ_j m_j (x_i − x_j) W(|x_ij|, h). Their pair force −κ m_j (x_i − x_j) W is
/// antisymmetric only for equal masses; adaptive sampling breaks that, so this uses the symmetric
/// variant f_ij = −κ' m_i m_j (x_i − x_j) W_poly6(|x_ij|, h̄), h̄ = (h_i + h_j)/2, κ' = κ/m_ref,
/// which equals Becker & Teschner for uniform mass m_ref (docs/equations.md, "Surface tension").
/// `si`: the support h_i (h̄ = h_i exactly when h_j = h_i).
/// The factor −κ' m_i m_j W_poly6(|x_ij|, h̄) of (x_i − x_j) in f_ij.
inline double surface_tension_pair_coefficient(double kappa_prime, double mi, double mj, double W) {
  return -kappa_prime * mi * mj * W;
}

template <int D>
inline Vec<D> surface_tension_pair_force(double kappa_prime, double mi, double mj, const Vec<D>& d, double r,
                                         const kernel::Support<D>& si, double hj) {
  const double W = si.h == hj ? kernel::poly6<D>(r, si) : kernel::poly6<D>(r, 0.5 * (si.h + hj));
  return surface_tension_pair_coefficient(kappa_prime, mi, mj, W) * d;
}

}  // namespace sc
