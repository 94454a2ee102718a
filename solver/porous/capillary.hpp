// Capillary potential and the SPH gradient of a porous scalar field (Lenaerts et al. 2008 eqs 3-4).
#pragma once
#include <cmath>
#include <utility>

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

/// The sums of porous_gradient for one field: Σ_j terms and the moment matrix of L_i.
template <int D>
class PorousGradientSum {
 public:
  /// Adds neighbour j's term: A_j − A_i (Corrected) or A_j (Lenaerts), its V_j gradW_ij(h_j), d = x_i − x_j.
  void add(double A, const Vec<D>& grad, const Vec<D>& d) {
    g_ += A * grad;
    M_ += grad * (-d).transpose();
  }
  Vec<D> gradient(PorousGradient form) const {
    if (form == PorousGradient::Lenaerts) return g_;
    const Eigen::FullPivLU<Mat<D>> lu(M_);
    // A neighbourhood that does not span the space (a row, a lone pair) keeps the raw difference form.
    return lu.rank() == D && std::abs(M_.determinant()) > 1e-3 * std::pow(M_.norm(), D) ? Vec<D>(lu.solve(g_)) : g_;
  }

 private:
  Vec<D> g_ = Vec<D>::Zero();
  Mat<D> M_ = Mat<D>::Zero();
};

/// The gradient of [thesis eq. 22] (Lenaerts eq 3; the form as in porous_gradient below) of two
/// fields in one pass over the neighbours:
/// A over those with `a_part`, and, when `with_b`, B over those with `b_part`, a superset of
/// `a_part`. Returns {∇A_i, ∇B_i} (∇B_i = 0 without B).
template <int D>
std::pair<Vec<D>, Vec<D>> porous_gradients(const ParticleSet<D>& ps, const NeighbourGrid<D>& nb,
                                           const std::vector<double>& A, const std::vector<std::uint8_t>& a_part,
                                           const std::vector<double>& B, const std::vector<std::uint8_t>& b_part,
                                           bool with_b, std::size_t i, PorousGradient form) {
  const bool lenaerts = form == PorousGradient::Lenaerts;
  const double Ai = lenaerts ? 0.0 : A[i], Bi = lenaerts ? 0.0 : B[i];
  PorousGradientSum<D> sum_a, sum_b;
  for (const auto j : nb.of(i)) {
    if (j == i || !b_part[j] || !(with_b || a_part[j])) continue;
    const Vec<D> d = ps.x[i] - ps.x[j];
    const Vec<D> grad = ps.volume(j) * kernel::spiky_gradient<D>(d, d.norm(), ps.h[j]);
    if (a_part[j]) sum_a.add(A[j] - Ai, grad, d);
    if (with_b) sum_b.add(B[j] - Bi, grad, d);
  }
  return {sum_a.gradient(form), with_b ? sum_b.gradient(form) : Vec<D>::Zero()};
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
  return porous_gradients(ps, nb, A, takes_part, A, takes_part, false, i, form).first;
}

}  // namespace sc
