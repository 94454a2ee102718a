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

/// Mass with which neighbour j enters the density sum of particle i (eq 6 at a material interface).
/// A wall particle next to sand counts with the sand's rest density (its mass scaled by ρ0_i/ρ0_j),
/// so sand (ρ0 = 2650) at a wall built for water is not deficient. A sand particle next to water
/// counts as the water that would fill its rest volume, m_j ρ^f/ρ0_j with ρ^f = `water_rest_density`
/// (the multi-phase density of Solenthaler & Pajarola 2008, which sums volumes, not masses, across
/// an interface; not in the thesis): with its own mass (ρ0 = 2000) a full water particle beside sand
/// reads up to 1.5 ρ^f, 16 times the Tait stiffness B, and a small water particle (porous
/// absorption or emission, whose ρ0 is lowered by the missing mass) reads ρ/ρ0 ≈ 2.8 there
/// (measured in thesis_duck: p = 6.9 MPa, the particle shot off at 180 m/s and blew the run up).
/// `water_rest_density` = 0 keeps sand's own mass. Water keeps a wall's own mass (porous flow
/// lowers a water particle's rest density as it drains).
template <int D>
double neighbour_density_mass(const ParticleSet<D>& ps, std::size_t i, std::size_t j, double water_rest_density) {
  const Phase phase_i = ps.phase_of(i);
  if (phase_i == Phase::Sand && !ps.moves(j) && ps.rho0[j] != ps.rho0[i]) return ps.m[j] * (ps.rho0[i] / ps.rho0[j]);
  if (phase_i == Phase::Water && water_rest_density > 0.0 && ps.phase_of(j) == Phase::Sand)
    return ps.m[j] * (water_rest_density / ps.rho0[j]);
  return ps.m[j];
}

/// Density by summation [thesis eq. 6] (Müller 2003): ρ_i = Σ_j m_j W(|x_ij|, h_i), the
/// gather form with the particle's own support, self term included (W: see DensityKernel), with
/// the interface masses of neighbour_density_mass.
/// Written for every moving particle; boundary particles keep the density of their wall model.
template <int D>
double density_sum(const ParticleSet<D>& ps, const NeighbourGrid<D>& nb, std::size_t i,
                   kernel::DensityKernel k = kernel::DensityKernel::Spiky, double water_rest_density = 0.0) {
  double rho = 0.0;
  for (const auto j : nb.of(i))
    rho += neighbour_density_mass(ps, i, j, water_rest_density) *
           kernel::density_kernel<D>(k, (ps.x[i] - ps.x[j]).norm(), ps.h[i]);
  return rho;
}

template <int D>
void compute_density(ParticleSet<D>& ps, const NeighbourGrid<D>& nb, kernel::DensityKernel k,
                     double water_rest_density = 0.0) {
  const auto n = static_cast<std::int64_t>(ps.size());
  // Dynamic: the work per particle varies (walls, free surface) and moving particles are stored first.
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t i = 0; i < n; ++i)
    if (ps.moves(i)) ps.rho[i] = density_sum(ps, nb, i, k, water_rest_density);
}

}  // namespace sc
