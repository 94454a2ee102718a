// First-order kernel-gradient correction (Bonet & Lok 1999): the SPH pressure gradient is exact
// for linear fields where the smallest eigenvalue of a particle's moment matrix is at least 0.8 of
// a full lattice neighbourhood's (every particle of a resting lattice interior), and blends back to
// the uncorrected kernel below 0.6 of it (a flat free surface lies at one half), see CorrectionBand.
#pragma once
#include <algorithm>
#include <array>
#include <vector>

#include "core/particle_set.hpp"
#include "core/smallest_eigenvalue.hpp"
#include "neighbours/neighbour_grid.hpp"
#include "sph/kernels.hpp"
#include "sph/lattice_sum.hpp"
#include "sph/neighbour_batch.hpp"

namespace sc {

template <int D>
using MatArray = std::vector<Mat<D>, Eigen::aligned_allocator<Mat<D>>>;

/// Whether the symmetric A (upper triangle read) is positive definite, by Sylvester's criterion:
/// every leading principal minor is positive.
inline bool positive_definite(const Mat<2>& A) {
  return A(0, 0) > 0.0 && A(0, 0) * A(1, 1) - A(0, 1) * A(0, 1) > 0.0;
}
inline bool positive_definite(const Mat<3>& A) {
  if (!(A(0, 0) > 0.0 && A(0, 0) * A(1, 1) - A(0, 1) * A(0, 1) > 0.0)) return false;
  const double det = A(0, 0) * (A(1, 1) * A(2, 2) - A(1, 2) * A(1, 2)) - A(0, 1) * (A(0, 1) * A(2, 2) - A(1, 2) * A(0, 2)) +
                     A(0, 2) * (A(0, 1) * A(1, 2) - A(1, 1) * A(0, 2));
  return det > 0.0;
}

/// The blend weight of gradient_correction: clamp((λ − none)/(full − none), 0, 1) for the smallest
/// eigenvalue λ of the symmetric S, in closed form (core/smallest_eigenvalue.hpp; cheaper than an
/// iterative eigen-solver). Most particles are settled without it:
/// λ > full when S − (full + δ) I is positive definite, λ < none when a diagonal entry is below
/// none − δ (λ ≤ min_k S_kk). With δ = kMargin |S| far above the rounding of either test and of
/// the closed form, the weight is the closed form's, bitwise: exactly 1 (or 0).
template <int D>
double correction_weight(const Mat<D>& S, double none, double full) {
  constexpr double kMargin = 1e-9;
  const double margin = kMargin * S.cwiseAbs().maxCoeff();
  if (positive_definite(Mat<D>(S - (full + margin) * Mat<D>::Identity()))) return 1.0;
  if (S.diagonal().minCoeff() <= none - margin) return 0.0;
  return std::clamp((smallest_eigenvalue(S) - none) / (full - none), 0.0, 1.0);
}

/// The moment matrix M_i = Σ_j V_j ∇W_ij ⊗ (x_j − x_i) of gradient_correction, with the spiky
/// gradient averaged over both supports. Each term is −V_j W'(r)/r d dᵀ (d = x_i − x_j): symmetric,
/// so only the upper triangle is summed (with one division per pair) and then mirrored, and M is
/// exactly symmetric. The pairs go in batches (sph/neighbour_batch.hpp): the factor
/// −m_j W'(r) / (ρ_j r) of a batch is computed in one vectorised loop when every neighbour has
/// the support h_i, pair by pair otherwise.
template <int D>
Mat<D> moment_matrix(const ParticleSet<D>& ps, const NeighbourGrid<D>& nb, std::size_t i) {
  std::array<double, D * (D + 1) / 2> upper{};  // row by row; a local, so it stays in registers
  const kernel::Support<D> si(ps.h[i]);
  for_each_batch<D>(nb.of(i), ps.x[i], ps.x.data(), [&](const NeighbourBatch<D>& b) {
    constexpr int K = NeighbourBatch<D>::kSize;
    alignas(32) double hj[K], mj[K], rhoj[K], factor[K];
    b.gather(ps.h.data(), hj);
    b.gather(ps.m.data(), mj);
    b.gather(ps.rho.data(), rhoj);
    const auto factor_of = [&](int k, double dw) {  // i itself (r = 0) has no direction: no term
      const double r = b.r[k] > 0.0 ? b.r[k] : 1.0;
      const double f = -(mj[k] * dw) / (rhoj[k] * r);
      return b.r[k] > 0.0 ? f : 0.0;
    };
    if (b.all_equal(hj, si.h)) {
      for (int k = 0; k < b.size; ++k) factor[k] = factor_of(k, kernel::spiky_derivative<D>(b.r[k], si));
    } else {
      for (int k = 0; k < b.size; ++k)
        factor[k] = factor_of(k, kernel::pair_average([&](const kernel::Support<D>& s) { return kernel::spiky_derivative<D>(b.r[k], s); }, si, hj[k]));
    }
    for (int k = 0; k < b.size; ++k) {
      if (!(b.r[k] > 0.0)) continue;
      int c = 0;
      for (int a = 0; a < D; ++a)
        for (int e = a; e < D; ++e) upper[c++] += (factor[k] * b.d[a][k]) * b.d[e][k];
    }
  });
  Mat<D> M;
  int k = 0;
  for (int a = 0; a < D; ++a)
    for (int b = a; b < D; ++b) M(a, b) = M(b, a) = upper[k++];
  return M;
}

/// The moment matrix of a particle inside a resting lattice block, λ_full 𝟙: the lattice of spacing
/// dx, the support h = support_ratio dx, and masses that give the lattice the rest density by the
/// density kernel `kind` (scene/scene_builder.hpp lattice_mass), so V_j = 1 / Σ_k W_kind(r_k) in
/// units of dx^D, and λ_full = Σ_j V_j (−W'(r_j)/r_j) x_j² (spiky derivative W', x_j one coordinate
/// of the offset), independent of dx. The continuum's moment matrix is 𝟙; a lattice's falls short
/// of it, by about 30 % in 2-D with the spiky density kernel at h = 2 dx.
template <int D>
double full_moment(double support_ratio, kernel::DensityKernel kind) {
  const double h = support_ratio;  // in units of dx
  const double density = lattice_density_sum<D>(1.0, h, kind);
  const double moment = lattice_sum<D>(1.0, h, [&](const Vec<D>& d, double r) {
    return r > 0.0 ? -kernel::spiky_derivative<D>(r, kernel::Support<D>(h)) / r * d[0] * d[0] : 0.0;
  });
  return moment / density;
}

/// The band of λ_min(M) over which the correction blends in (gradient_correction), as fractions of
/// a full neighbourhood's λ_full (full_moment), each end a margin away from the two neighbourhoods
/// it must tell apart: above 0.8 λ_full the particle is corrected fully, so every particle of a
/// lattice interior (λ_full) is; below 0.6 λ_full not at all, so a particle at a flat free surface
/// is not. Across a flat surface the neighbourhood is half a full one, λ_min = λ_full/2 exactly,
/// and compression raises it (by about 2 % of λ_full at 3 % closer spacing): with the lower end at
/// λ_full/2 itself, any compressed surface would blend in the correction of a direction it has no
/// neighbours in.
struct CorrectionBand {
  double none, full;
  static CorrectionBand of_full_moment(double lambda_full) { return {0.6 * lambda_full, 0.8 * lambda_full}; }
};

/// Correction matrix L_i = M_i⁻¹ (moment_matrix), so that Σ_j V_j (A_j − A_i) L_i ∇W_ij = ∇A exactly
/// for a linear field A.
/// Where the neighbourhood is incomplete (free surface) the moment matrix loses rank; there L_i
/// blends continuously to I (the uncorrected kernel) as the smallest eigenvalue λ of the moment
/// matrix falls from `band.full` to `band.none`: L = (1 − w) I + w M⁻¹,
/// w = clamp((λ − none)/(full − none)). A hard switch would make surface particles flicker between
/// the two forces and stir the surface of a resting tank (test
/// water/correction_weight_is_the_clamped_smallest_eigenvalue).
template <int D>
Mat<D> gradient_correction(const ParticleSet<D>& ps, const NeighbourGrid<D>& nb, std::size_t i, CorrectionBand band) {
  const Mat<D> M = moment_matrix(ps, nb, i);
  const double w = correction_weight(M, band.none, band.full);
  if (w == 0.0) return Mat<D>::Identity();
  return (1.0 - w) * Mat<D>::Identity() + w * M.inverse();
}

/// A pair term t (a force built from ∇W_ij) corrected symmetrically, ½(L_i + L_j) t, written
/// ½((L_i + L_j) t): halving is exact in binary floating point (barring subnormals), so both orders
/// give the same bits (Eigen already pulls the scalar out of the product). Shared by the water,
/// sand and frictional pair loops.
template <int D>
inline Vec<D> corrected_pair_term(const Mat<D>& Li, const Mat<D>& Lj, const Vec<D>& t) {
  return 0.5 * ((Li + Lj) * t);
}

/// L_i (gradient_correction) of every moving particle, 𝟙 for the others.
template <int D>
void compute_gradient_corrections(const ParticleSet<D>& ps, const NeighbourGrid<D>& nb, CorrectionBand band, MatArray<D>& L) {
  L.resize(ps.size());
  const auto n = static_cast<std::int64_t>(ps.size());
  // Dynamic: the work per particle varies (walls, free surface) and moving particles are stored first.
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t i = 0; i < n; ++i) L[i] = ps.moves(i) ? gradient_correction(ps, nb, i, band) : Mat<D>::Identity();
}

}  // namespace sc
