// First-order kernel-gradient correction (Bonet & Lok 1999), used to make the SPH pressure
// gradient exact for linear fields in the interior.
#pragma once
#include <vector>

#include "core/particle_set.hpp"
#include "neighbours/neighbour_grid.hpp"
#include "sph/kernels.hpp"

namespace sc {

template <int D>
using MatArray = std::vector<Mat<D>, Eigen::aligned_allocator<Mat<D>>>;

/// Correction matrix L_i = (Σ_j V_j ∇W_ij ⊗ (x_j − x_i))⁻¹ with the spiky gradient averaged over
/// both supports, so that Σ_j V_j (A_j − A_i) L_i ∇W_ij = ∇A exactly for a linear field A.
/// Where the neighbourhood is incomplete (free surface: the smallest eigenvalue of the moment
/// matrix below `min_eigenvalue`) or the particle does not move, L_i = I, the uncorrected kernel.
template <int D>
Mat<D> gradient_correction(const ParticleSet<D>& ps, const NeighbourGrid<D>& nb, std::size_t i,
                           double min_eigenvalue = 0.5) {
  Mat<D> M = Mat<D>::Zero();
  for (const auto j : nb.of(i)) {
    if (j == i) continue;
    const Vec<D> d = ps.x[i] - ps.x[j];
    const double r = d.norm();
    const Vec<D> grad = 0.5 * (kernel::spiky_gradient<D>(d, r, ps.h[i]) + kernel::spiky_gradient<D>(d, r, ps.h[j]));
    M += ps.volume(j) * grad * (-d).transpose();
  }
  const Mat<D> S = 0.5 * (M + M.transpose());
  if (Eigen::SelfAdjointEigenSolver<Mat<D>>(S, Eigen::EigenvaluesOnly).eigenvalues().minCoeff() < min_eigenvalue)
    return Mat<D>::Identity();
  return M.inverse();
}

template <int D>
void compute_gradient_corrections(const ParticleSet<D>& ps, const NeighbourGrid<D>& nb, MatArray<D>& L) {
  L.resize(ps.size());
  const auto n = static_cast<std::int64_t>(ps.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) L[i] = ps.moves(i) ? gradient_correction(ps, nb, i) : Mat<D>::Identity();
}

}  // namespace sc
