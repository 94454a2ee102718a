// Frictional force between flowing sand particles (Solenthaler et al. 2007 after Müller 2004,
// applied to Zhu & Bridson's frictional stress as in the thesis §3.3).
#pragma once
#include "sand/strain_rate.hpp"

namespace sc {

/// Force on particle i of the pair (i, j) from the frictional stresses of both [thesis eq. 19],
/// with d_ij of [thesis eq. 20], in newtons (corrected form 19′ of docs/equations.md):
///   the force on j from i's stress is f_ji = −V_i Σ_i d_ij and i takes the reaction −Σ_j f_ji, so
///   f_i ← −V_j Σ_j d_ji + V_i Σ_i d_ij,
/// where Σ = −σ_f is the stress in the tension-positive convention. Errata of eq 19: (a) it is
/// −∇_{u_j}U_i, the gradient with respect to u_j; (b) the reaction on i is missing in the thesis,
/// without it momentum is not conserved; (c) the factor 2 belongs to Müller's strain JᵀJ − I and is
/// dropped for a Cauchy stress; (d) the formula is tension-positive while σ_f (eq 8) is
/// compression-positive: plugged in literally friction does positive work. The linearised form
/// (J = I) is used. The pair term is antisymmetric (f_ji = −f_ij), and with G_i of eq 9′ the total
/// power is Σ_i f_i·v_i = −Σ_i V_i Σ_i : D_i = −Σ_i V_i √3 sin φ p_i |D_i|_F ≤ 0.
/// `d` is x_i − x_j; Si, Sj are the tension-positive stresses Σ_i, Σ_j; si, sj the supports.
template <int D>
inline Vec<D> frictional_pair_force(double Vi, double Vj, const Mat<D>& Si, const Mat<D>& Sj, const Vec<D>& d,
                                    double r, const kernel::Support<D>& si, const kernel::Support<D>& sj) {
  return -Vj * (Sj * d_ij<D>(Vi, Vec<D>(-d), r, si)) + Vi * (Si * d_ij<D>(Vj, d, r, sj));
}

}  // namespace sc
