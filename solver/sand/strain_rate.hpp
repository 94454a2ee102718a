// Velocity gradient and strain rate of sand particles (SPH, after Solenthaler et al. 2007).
#pragma once
#include "core/particle_set.hpp"
#include "sand/rigid_body.hpp"
#include "neighbours/neighbour_grid.hpp"
#include "sph/kernels.hpp"

namespace sc {

/// d_ij = V_j ∇W(x_j − x_i, h_j) [thesis eq. 20], read with the convention of docs/equations.md §0:
/// the gradient is taken with respect to x_i, so d_ij = V_j gradW_ij(h_j) points from i towards j
/// (erratum 20: evaluating a gradient function literally at x_j − x_i flips the sign).
/// `d` is x_i − x_j. Spiky kernel gradient.
template <int D>
inline Vec<D> d_ij(double Vj, const Vec<D>& d, double r, const kernel::Support<D>& sj) {
  return Vj * kernel::spiky_gradient<D>(d, r, sj);
}

/// Velocity gradient [thesis eq. 9] (corrected form 9′ of docs/equations.md):
///   G_i = ∇v_i = Σ_j V_j (v_j − v_i) ⊗ gradW_ij(h_j),   (row: velocity component, column: ∂/∂x)
/// over the sand neighbours j of sand particle i, for the velocity field `v` (default: ps.v). Errata of eq 9: (a) the thesis omits −v_i, so a
/// uniform translation would show a gradient wherever the neighbourhood is not symmetric (free
/// surfaces); (b) it uses v_j Δt, a dimensionless increment, where the strain *rate* (1/s) is needed
/// by eq 12a; (d) the sign holds only with gradients taken with respect to x_i (§0).
template <int D>
Mat<D> velocity_gradient(const ParticleSet<D>& ps, const NeighbourGrid<D>& nb, std::size_t i,
                         const VecArrayOf<D>* velocities = nullptr) {
  const VecArrayOf<D>& v = velocities ? *velocities : ps.v;
  Mat<D> G = Mat<D>::Zero();
  const Vec<D> xi = ps.x[i], vi = v[i];
  const kernel::Support<D> si(ps.h[i]);
  for (const auto j : nb.of(i)) {
    if (j == i || ps.phase_of(j) != Phase::Sand) continue;
    const Vec<D> d = xi - ps.x[j];
    G += (v[j] - vi) * d_ij<D>(ps.volume(j), d, d.norm(), kernel::support_of<D>(ps.h[j], si)).transpose();
  }
  return G;
}

/// Strain rate D = (G + Gᵀ)/2 [1/s] (thesis, unnumbered under eq 8, built from eq 9′).
template <int D>
inline Mat<D> strain_rate(const Mat<D>& G) {
  return 0.5 * (G + G.transpose());
}

}  // namespace sc
