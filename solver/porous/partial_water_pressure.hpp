// Pressure and density of partial water particles: water particles much lighter than a full one,
// because porous absorption is draining them or emission is filling them (solver/porous/porous_flow.hpp).
#pragma once
#include <cmath>

#include "core/particle_set.hpp"
#include "neighbours/neighbour_grid.hpp"
#include "sph/kernels.hpp"

namespace sc {

/// A water particle is partial (a parcel) below this fraction of a full particle's mass. Particles
/// that are nearly full keep the state equation: a pond over a porous bed is mostly a little short
/// of m0, and treated as parcels it would lose its stiffness.
inline constexpr double kPartialWaterFraction = 0.5;

/// Mass of a full water particle at particle i's sampling level, m0 2^level (ParticleSet::level),
/// with m0 the mass of a full particle of the scene's sampling.
template <int D>
double full_mass_at_level(const ParticleSet<D>& ps, std::size_t i, double m0) {
  return std::ldexp(m0, ps.level[i]);
}

/// Rest density of a water particle of mass m, part of a full particle of mass `full` whose
/// density kernel at distance 0 is `self_kernel` = W(0, h_i) (ours [I]): ρ0 = ρ^f − (full − m) W(0, h_i).
/// In the density sum of eq 6 the self term m W(0, h) is most of ρ (about 80 % with the spiky kernel
/// at h = 2 dx), so without this a half-absorbed particle sits deep in tension, has zero pressure and
/// lets the pond sink into the porous bed; with it the particle is at rest where a full one would
/// be. A full particle of any level gets ρ^f.
inline double partial_water_rest_density(double fluid_density, double full, double m, double self_kernel) {
  return fluid_density - (full - m) * self_kernel;
}

/// True for a water particle holding less than kPartialWaterFraction of the mass of a full particle
/// at its level (m0 2^level).
template <int D>
bool is_partial_water(const ParticleSet<D>& ps, std::size_t i, double m0) {
  return ps.phase_of(i) == Phase::Water && ps.m[i] < kPartialWaterFraction * full_mass_at_level(ps, i, m0);
}

/// Replaces the state-equation pressure of every partial water particle i by the pressure of the
/// full water around it, the Shepard average p_i = Σ_j V_j p_j W_ij / Σ_j V_j W_ij over its full
/// water neighbours j (poly6 kernel, support h_i); one without full water neighbours (in the pores
/// of sand, or a droplet) keeps its own pressure, which holds it off walls and sand. Ours, not in
/// the thesis or Lenaerts et al. 2008: a partial particle is a parcel of the surrounding water, but
/// its own summation density (eq 6) is dominated by its neighbours (its self term is small), so a
/// neighbour closer than the lattice spacing drives ρ_i/ρ0_i far above 1 and the Tait pressure
/// (×(ρ/ρ0)^7) with it, far above the pressure of the water around it, which throws the parcel
/// out (test porous/partial_water_takes_the_pressure_of_the_water_around_it). Full particles keep
/// their own pressure. Gather: reads the pressures of full particles only,
/// writes those of partial ones.
template <int D>
void set_partial_water_pressure(ParticleSet<D>& ps, const NeighbourGrid<D>& nb, double m0) {
  const auto n = static_cast<std::int64_t>(ps.size());
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t i = 0; i < n; ++i) {
    if (!is_partial_water(ps, i, m0)) continue;
    double weight = 0.0, sum = 0.0;
    for (const auto j : nb.of(i)) {
      if (ps.phase_of(j) != Phase::Water || is_partial_water(ps, j, m0)) continue;
      const double w = ps.volume(j) * kernel::poly6<D>((ps.x[i] - ps.x[j]).norm(), ps.h[i]);
      weight += w;
      sum += w * ps.p[j];
    }
    if (weight > 0.0) ps.p[i] = sum / weight;
  }
}

/// Replaces the summation density (eq 6) of every partial water particle i by the density a full
/// particle would read at its place, ρ_i + ρ^f − ρ0_i = ρ_i + (m_full − m_i) W(0, h_i) (its rest
/// density is partial_water_rest_density), so that its
/// volume m_i/ρ_i in the pressure, viscosity and contact sums is the share of the water it is a
/// parcel of, and its acceleration F_i/m_i = (V_i/m_i) Σ_j V_j (P_i + P_j) ∇W_ij (eq 4) is that of
/// a full particle at the same place. Ours, not in the thesis or Lenaerts et al. 2008. Its own sum
/// lacks most of the self term, and among sand or at the free surface it has few water neighbours,
/// so its own summation density can be a small fraction of ρ^f and its volume m_i/ρ_i as large as
/// a full particle's for a few percent of the mass: the pressure around it would then accelerate it
/// far more than a full particle (test porous/partial_water_accelerates_like_a_full_particle_at_its_place).
/// Call after the pressures are set (a parcel without full neighbours keeps the state-equation
/// pressure of its own ρ_i/ρ0_i).
template <int D>
void set_partial_water_density(ParticleSet<D>& ps, double m0, double fluid_density) {
  const auto n = static_cast<std::int64_t>(ps.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i)
    if (is_partial_water(ps, i, m0)) ps.rho[i] += fluid_density - ps.rho0[i];
}

}  // namespace sc
