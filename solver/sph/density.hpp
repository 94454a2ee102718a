// SPH interpolation and density summation.
#pragma once
#include <span>

#include "core/particle_set.hpp"
#include "neighbours/neighbour_grid.hpp"
#include "sph/kernels.hpp"

namespace sc {

/// SPH interpolation [thesis eq. 1] (Monaghan 1992; Müller 2003):
/// A(x_i) = Σ_j V_j A_j W(|x_ij|, h_j), V_j = m_j/ρ_j, including j = i, with the neighbour's own
/// support h_j (scatter form, Lenaerts 2008 eq 1). Erratum: the thesis text calls ρ_j "the density
/// of particle i"; it is the density of particle j.
template <int D>
double interpolate(const ParticleSet<D>& ps, const NeighbourGrid<D>& nb, std::span<const double> field,
                   std::size_t i) {
  double sum = 0.0;
  for (const auto j : nb.of(i)) {
    const double r = (ps.x[i] - ps.x[j]).norm();
    sum += ps.volume(j) * field[j] * kernel::poly6<D>(r, ps.h[j]);
  }
  return sum;
}

/// Density by summation [thesis eq. 6] (Müller 2003): ρ_i = Σ_j m_j W(|x_ij|, h_i), the
/// gather form with the particle's own support, self term included (W: see DensityKernel).
/// Written for every moving particle; boundary particles keep the density of their wall model.
template <int D>
double density_sum(const ParticleSet<D>& ps, const NeighbourGrid<D>& nb, std::size_t i,
                   kernel::DensityKernel k = kernel::DensityKernel::Spiky) {
  double rho = 0.0;
  for (const auto j : nb.of(i)) {
    // A wall particle samples the sand next to it: it counts with the sand's rest density (its mass
    // scaled by ρ0_i/ρ0_j), so sand (ρ0 = 2650) at a wall built for water is not deficient. Water
    // keeps the wall's own mass (porous flow lowers a water particle's rest density as it drains).
    const bool rescale = ps.phase_of(i) == Phase::Sand && !ps.moves(j) && ps.rho0[j] != ps.rho0[i];
    const double mj = rescale ? ps.m[j] * (ps.rho0[i] / ps.rho0[j]) : ps.m[j];
    rho += mj * kernel::density_kernel<D>(k, (ps.x[i] - ps.x[j]).norm(), ps.h[i]);
  }
  return rho;
}

template <int D>
void compute_density(ParticleSet<D>& ps, const NeighbourGrid<D>& nb, kernel::DensityKernel k) {
  const auto n = static_cast<std::int64_t>(ps.size());
  // Dynamic: the work per particle varies (walls, free surface) and moving particles are stored first.
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t i = 0; i < n; ++i)
    if (ps.moves(i)) ps.rho[i] = density_sum(ps, nb, i, k);
}

}  // namespace sc
