// Pressure and density of partial water particles: water particles much lighter than a full one,
// because porous absorption is draining them or emission is filling them (solver/porous/porous_flow.hpp).
#pragma once
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/particle_set.hpp"
#include "neighbours/neighbour_grid.hpp"
#include "sph/gradient_correction.hpp"
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

/// Weight of a water particle's own state equation in its pressure, density and kernel-gradient
/// correction (weight_partial_water_corrections; ours [I]): 0 for a parcel (is_partial_water: below
/// kPartialWaterFraction of a full particle at its level), 1 for a full particle, linear in the mass
/// between. Porous exchange changes a particle's mass by a small
/// amount per step, so its pressure must be continuous in the mass. With a switch at
/// kPartialWaterFraction, a parcel that the bed filled back across it went in one step from the
/// pressure of the water around it to the state-equation pressure of its own compression. That
/// compression is built up while it is a parcel: with no stiffness of its own it drifts into the
/// face of the porous bed and its neighbours close in (within about half a spacing of the bed's
/// particles), so at the switch ρ_i/ρ0_i reads tens of percent above 1 and the Tait law gives a
/// hundred times the pressure of the pond; the parcel and its neighbours were thrown out of the
/// pools at metres per second in one step (capillary_rise at 0.005 m; test
/// porous/a_parcel_filled_back_inside_the_bed_face_regains_its_pressure_gradually). Ramped over the
/// mass between the parcel's threshold and a full particle, the pressure of that compression builds
/// up over the filling, which takes many sound-crossing times of a particle, so the particle and its
/// neighbours move apart as it builds instead of being kicked apart. A full particle (weight exactly
/// 1) is untouched, bitwise.
template <int D>
double own_pressure_weight(const ParticleSet<D>& ps, std::size_t i, double m0) {
  const double fraction = ps.m[i] / full_mass_at_level(ps, i, m0);
  return std::clamp((fraction - kPartialWaterFraction) / (1.0 - kPartialWaterFraction), 0.0, 1.0);
}

/// Replaces the state-equation pressure P_i of every water particle i lighter than a full one by
/// P_i^env + w_i (P_i − P_i^env), w_i = own_pressure_weight: a parcel (w_i = 0) takes the pressure
/// P_i^env of the full water around it, the Shepard average Σ_j V_j p_j W_ij / Σ_j V_j W_ij over its
/// water neighbours j ≠ i that are not parcels (their state-equation pressures; poly6 kernel,
/// support h_i), and a particle between a parcel and a full one the mix, continuous in its mass
/// (own_pressure_weight says why). One without such neighbours but inside a fixed porous bed takes
/// the pore-water pressure of the bed around it, the same Shepard average of the bed particles'
/// P^p (porous/rigid_pore_pressure.hpp; the water around it is the bed's pore water): the bed takes
/// parcels in (add_partial_water_wall_contact), so one can sit among the bed's particles, closer
/// than the spacing, where its own state equation reads a compression of tens of percent and a
/// pressure of MPa that threw it and the pond out of darcy_column (test
/// porous/a_parcel_inside_a_fixed_bed_takes_the_pore_pressure_around_it). One with neither (in the
/// pores of moving sand, or a droplet) keeps its own pressure, which holds it off walls and sand. Ours, not in the thesis or Lenaerts
/// et al. 2008: a partial particle is a parcel of the surrounding water, but its own summation
/// density (eq 6) is dominated by its neighbours (its self term is small), so a neighbour closer
/// than the lattice spacing drives ρ_i/ρ0_i far above 1 and the Tait pressure (×(ρ/ρ0)^7) with it,
/// far above the pressure of the water around it, which throws the parcel out (test
/// porous/partial_water_takes_the_pressure_of_the_water_around_it). Full particles keep their own
/// pressure. Gather: the averages read only state-equation pressures (the new ones of the lighter
/// particles are kept aside until all are computed).
template <int D>
void set_partial_water_pressure(ParticleSet<D>& ps, const NeighbourGrid<D>& nb, double m0) {
  // Buffers kept by the calling thread between steps; the parallel loop reaches them through the
  // references (a thread_local named in the loop would be each thread's own).
  thread_local std::vector<std::size_t> lighter_buffer;
  thread_local std::vector<double> mixed_buffer;
  std::vector<std::size_t>& lighter = lighter_buffer;  // the water particles lighter than a full one, in index order
  std::vector<double>& mixed = mixed_buffer;
  lighter.clear();
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (ps.phase_of(i) == Phase::Water && own_pressure_weight(ps, i, m0) < 1.0) lighter.push_back(i);
  mixed.resize(lighter.size());
  const auto n = static_cast<std::int64_t>(lighter.size());
#pragma omp parallel for schedule(dynamic, 64)
  for (std::int64_t k = 0; k < n; ++k) {
    const std::size_t i = lighter[k];
    double weight = 0.0, sum = 0.0, bed_weight = 0.0, bed_sum = 0.0;
    for (const auto j : nb.of(i)) {
      if (j == i) continue;
      const double w = ps.volume(j) * kernel::poly6<D>((ps.x[i] - ps.x[j]).norm(), ps.h[i]);
      if (ps.phase_of(j) == Phase::Water && !is_partial_water(ps, j, m0)) {
        weight += w;
        sum += w * ps.p[j];
      } else if (ps.phase_of(j) == Phase::Boundary && ps.porosity[j] > 0.0) {
        bed_weight += w;
        bed_sum += w * ps.pore_pressure[j];
      }
    }
    const double own = own_pressure_weight(ps, i, m0);
    const double env = weight > 0.0 ? sum / weight : bed_weight > 0.0 ? bed_sum / bed_weight : ps.p[i];
    mixed[k] = own > 0.0 ? env + own * (ps.p[i] - env) : env;
  }
  for (std::size_t k = 0; k < lighter.size(); ++k) ps.p[lighter[k]] = mixed[k];
}

/// Replaces the summation density (eq 6) of every water particle i lighter than a full one by
/// ρ_i + (1 − w_i)(ρ^f − ρ0_i), w_i = own_pressure_weight: for a parcel (w_i = 0) the density a full
/// particle would read at its place, ρ_i + ρ^f − ρ0_i = ρ_i + (m_full − m_i) W(0, h_i) (its rest
/// density is partial_water_rest_density), so that its
/// volume m_i/ρ_i in the pressure, viscosity and contact sums is the share of the water it is a
/// parcel of, and its acceleration F_i/m_i = (V_i/m_i) Σ_j V_j (P_i + P_j) ∇W_ij (eq 4) is that of
/// a full particle at the same place. Ours, not in the thesis or Lenaerts et al. 2008. Its own sum
/// lacks most of the self term, and among sand or at the free surface it has few water neighbours,
/// so its own summation density can be a small fraction of ρ^f and its volume m_i/ρ_i as large as
/// a full particle's for a few percent of the mass: the pressure around it would then accelerate it
/// far more than a full particle (test porous/partial_water_accelerates_like_a_full_particle_at_its_place).
/// Between a parcel and a full particle the correction fades with the same weight as the pressure,
/// so that the volume, like the pressure, is continuous in the mass. Call after the pressures are
/// set (a parcel without full neighbours keeps the state-equation pressure of its own ρ_i/ρ0_i).
template <int D>
void set_partial_water_density(ParticleSet<D>& ps, double m0, double fluid_density) {
  const auto n = static_cast<std::int64_t>(ps.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    if (ps.phase_of(i) != Phase::Water) continue;
    const double own = own_pressure_weight(ps, i, m0);
    if (own < 1.0) ps.rho[i] += (1.0 - own) * (fluid_density - ps.rho0[i]);
  }
}

/// Weights the kernel-gradient correction L_i (sph/gradient_correction.hpp) of every water particle
/// lighter than a full one by its own-pressure weight w_i (own_pressure_weight): L_i ← (1 − w_i) 𝟙
/// + w_i L_i, so a parcel (w_i = 0) takes the uncorrected kernel and the correction returns with
/// the particle's own state equation, continuous in its mass. Ours, like the parcel model. The
/// correction renormalises the gradient of a pressure field that the particle samples with its
/// neighbours: Σ_j V_j (P_i + P_j) L_i ∇W_ij = Σ_j V_j (P_j − P_i) L_i ∇W_ij + 2 P_i L_i Σ_j V_j ∇W_ij,
/// where the second sum vanishes in a complete neighbourhood and is held in check by the particle's
/// own density where it does not (a particle pushed towards a gap reads less density and less
/// pressure). A parcel's pressure is not its own sample: it copies the water around it, so at the
/// face of a porous bed, where the parcels sit and their neighbourhoods are incomplete, that second
/// term has no restoring part and the correction would amplify it by up to 1/band.full (a lattice
/// interior's gain times 1.25); parcels and their neighbours were thrown out of the pools (test
/// porous/a_parcel_at_a_bed_face_takes_the_uncorrected_kernel).
template <int D>
void weight_partial_water_corrections(const ParticleSet<D>& ps, double m0, MatArray<D>& L) {
  const auto n = static_cast<std::int64_t>(ps.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    if (ps.phase_of(i) != Phase::Water) continue;
    const double own = own_pressure_weight(ps, i, m0);
    if (own < 1.0) L[i] = (1.0 - own) * Mat<D>::Identity() + own * L[i];
  }
}

}  // namespace sc
