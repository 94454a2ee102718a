// SPH density summation (the solver's interpolation, eq 1 with A = ρ).
#pragma once

#include "core/particle_set.hpp"
#include "neighbours/neighbour_grid.hpp"
#include "sph/kernels.hpp"

namespace sc {

/// Mass neighbour j brings into particle i's density sum (eq 6 across phases, ours [I]). Summed
/// by mass, another phase would read as a density jump, so two pairs count by volume instead, at
/// i's density:
/// - sand next to a wall particle or to sand of another rest density: j's mass scaled by
///   ρ0_i/ρ0_j, so sand (ρ0 = 2650) at a wall built for water is not deficient, and wet sand,
///   whose mass and rest density hold its pore water (eq 31, porous/wet_density.hpp), beside dry
///   sand reads neither compression nor tension at a wetting front (test
///   porous/a_resting_saturated_bed_has_the_wet_density_of_eq_31);
/// - water next to sand: the grain's volume m_j/ρ0_j at the water's rest density ρ^w (after
///   Solenthaler & Pajarola 2008, density-contrast SPH). Counted by mass, a water particle resting
///   on a sand bed would read up to (1 + 2.65)/2 of its rest density, an interface 2.65x stiffer
///   than the water the step is limited for, which shoots water squeezed between grains away
///   (test water/density_eq_6_of_water_on_sand_counts_the_grains_by_volume). ρ^w, not the
///   particle's own ρ0_i, which porous flow lowers as a water particle drains.
/// Water keeps a wall's own mass (walls are built for water).
template <int D>
double neighbour_mass(const ParticleSet<D>& ps, std::size_t i, std::size_t j, double water_rest_density) {
  const Phase pi = ps.phase_of(i), pj = ps.phase_of(j);
  if (pi == Phase::Sand && (pj == Phase::Sand || !ps.moves(j)) && ps.rho0[j] != ps.rho0[i])
    return ps.m[j] * (ps.rho0[i] / ps.rho0[j]);
  if (pi == Phase::Water && pj == Phase::Sand) return ps.m[j] * (water_rest_density / ps.rho0[j]);
  return ps.m[j];
}

/// Density by summation [thesis eq. 6] (Müller 2003): ρ_i = Σ_j m_j W(|x_ij|, h_i), the
/// gather form with the particle's own support, self term included (W: see DensityKernel; m_j:
/// see neighbour_mass). This is where the solver interpolates: SPH interpolation [thesis eq. 1]
/// (Monaghan 1992) A(x_i) = Σ_j V_j A_j W(|x_ij|, h), V_j = m_j/ρ_j, with A = ρ, so V_j A_j = m_j
/// (the thesis text calls ρ_j "the density of particle i"; it is that of particle j); eqs 4 and 5
/// are its gradient and Laplacian. Written for every moving particle; boundary particles keep the density of
/// their wall model.
template <int D>
double density_sum(const ParticleSet<D>& ps, const NeighbourGrid<D>& nb, std::size_t i, kernel::DensityKernel k,
                   double water_rest_density) {
  double rho = 0.0;
  const Vec<D> xi = ps.x[i];
  const kernel::Support<D> si(ps.h[i]);
  for (const auto j : nb.of(i))
    rho += neighbour_mass(ps, i, j, water_rest_density) * kernel::density_kernel<D>(k, (xi - ps.x[j]).norm(), si);
  return rho;
}

template <int D>
void compute_density(ParticleSet<D>& ps, const NeighbourGrid<D>& nb, kernel::DensityKernel k, double water_rest_density) {
  const auto n = static_cast<std::int64_t>(ps.size());
  // Dynamic: the work per particle varies (walls, free surface) and moving particles are stored first.
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t i = 0; i < n; ++i)
    if (ps.moves(i)) ps.rho[i] = density_sum(ps, nb, i, k, water_rest_density);
}

}  // namespace sc
