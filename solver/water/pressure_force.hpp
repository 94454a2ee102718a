// Pressure force between two particles of unequal supports (shooting/gathering).
#pragma once
#include "sph/kernels.hpp"

namespace sc {

/// Pressure force on particle i from j [thesis eq. 4] (symmetrised over both supports after
/// Desbrun & Cani / Adams 2007), in newtons:
///   f_ij = −V_i V_j (P_i + P_j) · (∇W_spiky(h_i) + ∇W_spiky(h_j))/2,
/// with d = x_i − x_j and gradients taken with respect to x_i (docs/equations.md §0), so a positive
/// pressure pushes the particles apart and f_ji = −f_ij (Newton's third law).
///
/// On the factor 2 (docs/equations.md lists the thesis' missing 1/2 as erratum 4a): we keep the thesis
/// form, because it is the one that is consistent. Writing P_j = P_i + δ_j,
///   Σ_j V_j (P_i + P_j) ∇W_ij = 2 P_i Σ_j V_j ∇W_ij + Σ_j V_j δ_j ∇W_ij ≈ 0 + ∇P
/// in the interior, which is the standard symmetric SPH form (Monaghan 1992, m_i m_j (P_i/ρ_i² +
/// P_j/ρ_j²) at equal densities). Müller 2003's average (P_i + P_j)/2 gives only ∇P/2: a column at
/// rest then carries twice the hydrostatic pressure. The unit test
/// water/pressure_force_reproduces_linear_gradient pins this. `mueller_half` = true selects
/// Müller's halved form (documented switch, for comparison only). `si`: the support h_i.
/// The factor −V_i V_j (P_i + P_j) (or Müller's half of it) of the averaged gradient in f_ij [thesis eq. 4].
inline double pressure_pair_coefficient(double Vi, double Vj, double Pi, double Pj, bool mueller_half = false) {
  const double pressure = mueller_half ? 0.5 * (Pi + Pj) : (Pi + Pj);
  return -Vi * Vj * pressure;
}

template <int D>
inline Vec<D> pressure_pair_force(double Vi, double Vj, double Pi, double Pj, const Vec<D>& d, double r,
                                  const kernel::Support<D>& si, double hj, bool mueller_half = false) {
  const Vec<D> grad = kernel::pair_average([&](const kernel::Support<D>& s) { return kernel::spiky_gradient<D>(d, r, s); }, si, hj);
  return pressure_pair_coefficient(Vi, Vj, Pi, Pj, mueller_half) * grad;
}

}  // namespace sc
