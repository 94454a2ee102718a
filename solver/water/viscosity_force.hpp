// Viscosity force between two particles of unequal supports.
#pragma once
#include "sph/kernels.hpp"

namespace sc {

/// Viscosity force on particle i from j [thesis eq. 5] (Müller 2003), in newtons:
///   f_ij = μ V_i V_j (v_j − v_i) (∇²W_visc(r, h_i) + ∇²W_visc(r, h_j))/2.
/// Correct as printed; symmetric in i and j, so f_ji = −f_ij, and it only damps relative motion.
/// μ [Pa s] is the SPH (artificial) viscosity of the case, not necessarily water's 1e-3 Pa s.
/// `si`: the support h_i.
/// The factor μ V_i V_j ∇̄²W of (v_j − v_i) in f_ij, for the averaged Laplacian `lap` [thesis eq. 5].
inline double viscosity_pair_coefficient(double mu, double Vi, double Vj, double lap) { return mu * Vi * Vj * lap; }

template <int D>
inline Vec<D> viscosity_pair_force(double mu, double Vi, double Vj, const Vec<D>& vi, const Vec<D>& vj,
                                   double r, const kernel::Support<D>& si, double hj) {
  const double lap = kernel::pair_average([r](const kernel::Support<D>& s) { return kernel::viscosity_laplacian<D>(r, s); }, si, hj);
  return viscosity_pair_coefficient(mu, Vi, Vj, lap) * (vj - vi);
}

}  // namespace sc
