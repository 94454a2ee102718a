// Parameters of the DEM grains after Rungjiratananon et al. 2008 ("Real-time animation of
// sand-water interaction", seed 003): contact, friction, wetness, liquid bridges and the coupling
// with the SPH water. SI units throughout; the paper's dimensionless wetness w is the grain's
// saturation s = (water held) / (water capacity), so that the wet factors (1 + w_i + w_j) and the
// threshold w_f keep the paper's meaning while the water itself is counted in kilograms.
#pragma once

namespace sc::dem {

/// Which cohesive law acts between two wet grains (solver/dem/contact_laws.hpp).
enum class BridgeLaw {
  None,
  Paper,    ///< k_bridge max(0, w_f - w̄)(v_j - v_i) while separating [Rungjiratananon 2008: liquid bridge]
  Willett,  ///< capillary force 2πRγcosθ/(1 + 2.1 s⁺ + 10 s⁺²) up to rupture [Willett 2000: eq. 12-13]
};

struct Params {
  // --- dry contact ---------------------------------------------------------------------------
  double stiffness = 0.0;            ///< normal spring k_s [N/m]
  double damping = 0.0;              ///< normal dashpot k_d of dry grains [N s/m]
  double friction = 0.5;             ///< grain-grain Coulomb coefficient μ
  double wall_friction = 0.5;        ///< grain-wall Coulomb coefficient
  double tangential_stiffness_ratio = 2.0 / 7.0;  ///< k_t/k_s of the tangential spring
  double tangential_damping = 0.0;   ///< tangential dashpot γ_t [N s/m]
  bool rotation = true;              ///< grains carry angular velocity (torques of tangential forces)
  double rolling_friction = 0.0;     ///< μ_r: rolling torque bound μ_r R_eff |F_n| (0 = off)
  double rolling_damping = 0.0;      ///< rolling dashpot γ_r [N m s]
  // --- wetness --------------------------------------------------------------------------------
  double water_density = 1000.0;     ///< [kg/m^3]
  double capacity_fraction = 0.4;    ///< water a grain holds at s = 1, as a fraction of its volume
  double radius_shrink = 0.0;        ///< k_r: radius lost at s = 1 [m]
  double min_radius_fraction = 0.8;  ///< the wet radius never falls below this fraction of R
  double wet_threshold = 0.5;        ///< w_f: saturation above which a grain is over-wet
  double propagation_rate = 0.0;     ///< k_p [1/s]; k_p Δt must stay <= 1
  // --- liquid bridges -------------------------------------------------------------------------
  BridgeLaw bridge = BridgeLaw::None;
  double bridge_coefficient = 0.0;   ///< k_bridge of the paper's law [N s/m]
  double bridge_range = 0.0;         ///< gap up to which the paper's bridge holds [m]
  double surface_tension = 0.072;    ///< γ of Willett's law [N/m]
  double contact_angle = 0.0;        ///< θ of Willett's law [rad]
  double bridge_liquid_fraction = 0.01;  ///< share of the pair's held water that forms one bridge (Willett)
  // --- coupling with the SPH water ------------------------------------------------------------
  double coupling_support = 0.0;     ///< kernel support h of the water-grain terms [m]
  double coupling_viscosity = 0.0;   ///< μ the water-grain viscous term carries (eq 5's pair viscosity) [Pa s]
  double grain_pressure = 0.0;       ///< p_g, the grain's constant pressure in the pressure term [Pa]
  double absorb_distance = 0.0;      ///< a water particle within R + this of a grain can be absorbed [m]
};

}  // namespace sc::dem
