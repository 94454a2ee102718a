// Parameters of the sand model (case file key "sand"), SI units.
#pragma once
#include <cmath>

#include "core/types.hpp"

namespace sc {

/// Which length enters the rigid stress [thesis eq. 12a].
enum class RigidStressLength {
  Spacing,  ///< the particle spacing s_i = V_i^(1/D) (Zhu & Bridson's grid cell, corrected form)
  Support,  ///< the kernel support h_i (the thesis as printed: erratum 12a, kept as a switch)
};

/// Which strength the yield test [thesis eq. 10] compares the trial stress with.
enum class YieldSurface {
  FlowConsistent,  ///< the strength of the flowing stress of eq 8: √3 σ̄ < (3/√2) sin φ σ_m + c (default)
  ZhuBridson,      ///< eq 10 as printed (Zhu & Bridson 2005): √3 σ̄ < sin φ σ_m + c (switch)
};

/// Which inertia tensor of a rigid cluster [thesis eq. 17] the cluster motion uses (3-D only).
enum class InertiaForm {
  Corrected,  ///< I = Σ m (|r'|² 𝟙 − r' r'ᵀ) (default)
  Printed,    ///< as printed (erratum 17): the second diagonal entry m(r'_y² + r'_z²) (switch)
};

struct SandParams {
  double rest_density = 2650.0;      ///< ρ0 of sand particles [kg/m^3] (bulk density)
  double friction_angle_deg = 30.0;  ///< φ [deg]; μ_f = sin φ in eqs 8 and 10
  double cohesion = 0.0;             ///< c [Pa] of the yield test, eq 10 (of dry sand)
  bool wet_cohesion_loss = true;     ///< c = c0 (1 − S) for wetted sand (porous/wet_cohesion.hpp)
  double viscosity = 0.0;            ///< viscosity of eq 5 between sand particles [Pa s] (numerical damping)
  double wall_friction = -1.0;       ///< Coulomb coefficient of rough walls; < 0: tan φ
  double contact_damping = 0.5;      ///< damping ratio ζ of the Bell et al. 2005 normal contact
  bool rigid_clusters = true;        ///< project non-yielding sand onto rigid motions (eqs 12b-18)
  RigidStressLength rigid_length = RigidStressLength::Spacing;
  YieldSurface yield_surface = YieldSurface::FlowConsistent;
  InertiaForm inertia = InertiaForm::Corrected;

  double sin_phi() const { return std::sin(friction_angle_deg * pi / 180.0); }
  double wall_mu() const { return wall_friction >= 0.0 ? wall_friction : std::tan(friction_angle_deg * pi / 180.0); }
};

}  // namespace sc
