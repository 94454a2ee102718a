// Capillary potential and the SPH gradient of a porous scalar field (Lenaerts et al. 2008 eqs 3-4).
#pragma once
#include <array>
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

/// The gradients of porous_gradient from the sums g = Σ_j V_j (A_j − A_i) gradW_ij (one per field)
/// and their common moment matrix M = Σ_j V_j gradW_ij ⊗ x_ji: L_i g with L_i = M⁻¹ (Corrected),
/// or g itself (Lenaerts). One factorisation serves every field.
template <int D, std::size_t K>
std::array<Vec<D>, K> corrected_gradients(const Mat<D>& M, std::array<Vec<D>, K> g, PorousGradient form) {
  if (form == PorousGradient::Lenaerts) return g;
  const Eigen::FullPivLU<Mat<D>> lu(M);
  // A neighbourhood that does not span the space (a row, a lone pair) keeps the raw difference form.
  if (lu.rank() == D && std::abs(M.determinant()) > 1e-3 * std::pow(M.norm(), D))
    for (Vec<D>& gk : g) gk = lu.solve(gk);
  return g;
}

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
  Vec<D> ga = Vec<D>::Zero(), gb = Vec<D>::Zero();
  Mat<D> Ma = Mat<D>::Zero(), Mb = Mat<D>::Zero();
  bool shared = true;  // B's sum has had only neighbours of A's so far: its moment matrix is Ma
  const kernel::Support<D> si(ps.h[i]);  // the neighbours' supports are mostly h_i: one lookup
  for (const auto j : nb.of(i)) {
    if (j == i || !b_part[j] || !(with_b || a_part[j])) continue;
    const Vec<D> d = ps.x[i] - ps.x[j];
    const double r = d.norm();
    const Vec<D> grad = ps.volume(j) * (ps.h[j] == si.h ? kernel::spiky_gradient<D>(d, r, si)
                                                         : kernel::spiky_gradient<D>(d, r, ps.h[j]));
    const Mat<D> moment = grad * (-d).transpose();
    if (a_part[j]) {
      ga += (A[j] - Ai) * grad;
      Ma += moment;
    }
    if (!with_b) continue;
    gb += (B[j] - Bi) * grad;
    if (shared && !a_part[j]) Mb = Ma;
    shared = shared && a_part[j];
    if (!shared) Mb += moment;
  }
  if (!with_b) return {corrected_gradients<D, 1>(Ma, {ga}, form)[0], Vec<D>::Zero()};
  if (shared) {
    const auto [a, b] = corrected_gradients<D, 2>(Ma, {ga, gb}, form);
    return {a, b};
  }
  return {corrected_gradients<D, 1>(Ma, {ga}, form)[0], corrected_gradients<D, 1>(Mb, {gb}, form)[0]};
}

/// Gradient of a porous field A at particle i [thesis eq. 22] (Lenaerts eq 3) over the neighbours
/// j with `takes_part[j]`, with the spiky gradient of the neighbour's support h_j, taken with
/// respect to x_i (docs/equations.md §0; the literal "∇W(x_j − x_i)" read as a function of x_j − x_i
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
