// Assembly of the fluid forces on every moving particle.
#pragma once
#include "core/particle_set.hpp"
#include "neighbours/neighbour_grid.hpp"
#include "sph/gradient_correction.hpp"
#include "sph/kernels.hpp"

namespace sc {

/// Parameters of the water model (case file key "water").
struct WaterParams {
  double rest_density = 1000.0;      ///< ρ0 [kg/m^3]
  double viscosity = 0.0;            ///< μ [Pa s], the dynamic viscosity eq 5 models
  double surface_tension = 0.0;      ///< κ [1/s^2] of Becker & Teschner 2007
  double reference_mass = 1.0;       ///< m_ref [kg] of the symmetric surface-tension form
  kernel::DensityKernel density_kernel = kernel::DensityKernel::Spiky;  ///< kernel of eq 6
  bool gradient_correction = true;   ///< symmetrised Bonet-Lok correction of the pressure gradient
  /// λ_full of the case's lattice (sph/gradient_correction.hpp full_moment), set by
  /// SimulationParams::from_case: the correction's blend band is a fraction of it.
  double full_moment = 1.0;
  /// The viscosity moment of the case's lattice (water/viscosity_force.hpp viscosity_moment), set
  /// by SimulationParams::from_case: eq 5's sum falls short of μ∇²v by this factor on a lattice,
  /// so the pair force carries μ divided by it. 1 = eq 5 as printed.
  double viscosity_moment = 1.0;
  /// The viscosity `mu` of a pair force of eq 5 that is to carry μ∇²v on the case's lattice
  /// (viscosity_pair_force).
  double pair_viscosity(double mu) const { return mu / viscosity_moment; }
  bool mueller_half_pressure = false;  ///< eq 4: Müller's (P_i + P_j)/2 instead of the thesis' P_i + P_j
};

/// Adds to ps.force the pair forces of eqs 4 and 5 and surface tension, for every moving particle,
/// from water and boundary neighbours. Boundary neighbours exert pressure (their wall-model
/// pressure) and, when rough, viscosity against their zero velocity. Surface tension acts between
/// water and water and between water and sand, on both partners: a moving sand particle gathers
/// the reaction of its water neighbours (pressure and viscosity between sand and water are
/// gathered by the sand's own forces, sand/sand_forces.hpp). Gather loop: each particle writes
/// only its own force.
template <int D>
void add_water_forces(ParticleSet<D>& ps, const NeighbourGrid<D>& nb, const WaterParams& params,
                      const MatArray<D>& correction);

/// Momentum balance [thesis eq. 2] ρ Dv/Dt = −∇P + ρg + μ∇²v, discretised per particle as
/// [thesis eq. 3] ρa = f^pressure + f^external + f^viscosity. Eq 3 is written per unit volume while
/// eqs 4 and 5 are forces in newtons (docs/equations.md, eq 3): the acceleration is a_i = F_i/m_i with
/// F_i = Σ_j (f_ij^p + f_ij^v) + m_i g + F_i^surface, with no second division by ρ.
template <int D>
inline Vec<D> acceleration(const Vec<D>& total_force, double mass) {
  return total_force / mass;
}

}  // namespace sc
