// Capillary potential and the SPH gradient of a porous scalar field (Lenaerts et al. 2008 eqs 3-4).
#pragma once
#include <cmath>

#include "core/particle_set.hpp"
#include "neighbours/neighbour_grid.hpp"
#include "porous/porous_params.hpp"
#include "sph/kernels.hpp"

namespace sc {

/// Capillary potential [thesis eq. 23] (Lenaerts eq 4): P^c = k^c (1 − S)^α, 0 < α < 1. Correct as
/// printed: P^c(0) = k^c, P^c(1) = 0, decreasing in S. It acts as a suction: the pore velocity
/// (eq 27) points up its gradient, towards drier particles.
inline double capillary_potential(double saturation, double kc, double alpha) {
  return kc * std::pow(1.0 - saturation, alpha);
}

/// Gradient of a porous field A at particle i [thesis eq. 22] (Lenaerts eq 3) over the neighbours
/// j with `takes_part[j]`, with the spiky gradient of the neighbour's support h_j, taken with
/// respect to x_i (EQUATIONS.md §0; the literal "∇W(x_j − x_i)" read as a function of x_j − x_i
/// would flip the sign).
/// - PorousGradient::Lenaerts: the printed form ∇A_i = Σ_j V_j A_j gradW_ij(h_j). It is correct in
///   the interior but gives a spurious gradient ~A/h at the edge of the porous body, also for a
///   constant A (and lopsided rows next to non-porous walls).
/// - PorousGradient::Corrected (default, ours): the difference form Σ_j V_j (A_j − A_i) L_i
///   gradW_ij(h_j) with L_i = (Σ_j V_j gradW_ij ⊗ x_ij)⁻¹, exact for linear fields wherever the
///   neighbourhood spans the space, so a porous column next to a wall or a free surface sees the
///   true gradient.
template <int D>
Vec<D> porous_gradient(const ParticleSet<D>& ps, const NeighbourGrid<D>& nb, const std::vector<double>& A,
                       const std::vector<std::uint8_t>& takes_part, std::size_t i, PorousGradient form) {
  Vec<D> g = Vec<D>::Zero();
  Mat<D> M = Mat<D>::Zero();
  for (const auto j : nb.of(i)) {
    if (j == i || !takes_part[j]) continue;
    const Vec<D> d = ps.x[i] - ps.x[j];
    const Vec<D> grad = ps.volume(j) * kernel::spiky_gradient<D>(d, d.norm(), ps.h[j]);
    if (form == PorousGradient::Lenaerts) {
      g += A[j] * grad;
    } else {
      g += (A[j] - A[i]) * grad;
      M += grad * (-d).transpose();
    }
  }
  if (form == PorousGradient::Lenaerts) return g;
  const Eigen::FullPivLU<Mat<D>> lu(M);
  // A neighbourhood that does not span the space (a row, a lone pair) keeps the raw difference form.
  return lu.rank() == D && std::abs(M.determinant()) > 1e-3 * std::pow(M.norm(), D) ? Vec<D>(lu.solve(g)) : g;
}

}  // namespace sc
