// Parameters of the porous-flow model (case file key "porous"; Lenaerts et al. 2008, thesis §3.4-3.5),
// SI units. The model's parameters map to a soil's hydraulic conductivity K_h = k ρ^f g / μ, suction
// head ψ and fillable porosity Δθ as documented in cases/README.md and in each porous case.
#pragma once
#include "sph/kernels.hpp"

namespace sc {

/// Which form of eq 22 computes ∇P^c (and ∇P^p).
enum class PorousGradient {
  Corrected,  ///< difference form Σ V_j (P_j − P_i) gradW_ij with the first-order correction (default)
  Lenaerts,   ///< the literal eq 22: Σ V_j P_j gradW_ij (spurious gradient at the body's boundary)
};

/// Which form of eq 28 diffuses the absorbed mass.
enum class PorousDiffusion {
  Conserving,       ///< pairwise upwind flux 28′ with occupied/free volume limiters (default, exact balance)
  LenaertsLiteral,  ///< eq 28 as printed (not conservative; m_p clamped to [0, capacity])
};

struct PorousParams {
  double fluid_density = 1000.0;  ///< ρ^fluid [kg/m^3] of the absorbed water
  double porosity = 0.4;          ///< φ0 of the undeformed skeleton, in (0, 1)
  double permeability = 1e-10;    ///< intrinsic permeability k [m^2] (eqs 26-27; the thesis' K)
  double fluid_viscosity = 1e-3;  ///< μ [Pa s] dynamic viscosity of the pore water (not the SPH viscosity)
  double capillary_constant = 0;  ///< k^c [Pa] of eq 23
  double capillary_exponent = 0.1;  ///< α in (0, 1] of eq 23
  double saturation_exponent = 7;   ///< β > 0 of eq 29 (Lenaerts: 7)
  double pore_stiffness = 0;      ///< k^p [Pa] of eq 25
  double pore_gamma = 7;          ///< γ of eq 25
  double stress_scale = 1;        ///< η of eq 32
  double initial_saturation = 0;  ///< S of every porous particle at the start
  double min_water_fraction = 0.01;  ///< water particles below this fraction of full mass are absorbed whole
  double create_fraction = 0.1;      ///< a new water particle is created once this fraction of a full one waits
  PorousGradient gradient = PorousGradient::Corrected;
  PorousDiffusion diffusion = PorousDiffusion::Conserving;
  bool thesis_pore_pressure_ratio = false;  ///< eq 25 with the thesis' inverted ρ0/ρ (erratum switch)
  // Derived when the simulation is set up (not case keys):
  double flux_length_factor = 0.6;  ///< λ: pair flux length L_ij = λ h̄_ij (diffusion.hpp)
  double water_mass = 0;            ///< m0: mass of a full-size water particle [kg]
  double water_support = 0;         ///< h0: support radius of a full-size water particle [m]
  double spacing = 0;               ///< particle spacing of the case [m]
  kernel::DensityKernel density_kernel = kernel::DensityKernel::Spiky;  ///< kernel of eq 6
};

}  // namespace sc
