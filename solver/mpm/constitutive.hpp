// The materials of two-grid MPM: sand as Hencky elasticity with Drucker-Prager plasticity, projected
// in log-strain space (Klár et al. 2016), with Tampubolon et al. 2017's volume correction and a
// cohesion that falls with saturation; water as a weakly compressible fluid on its volume ratio J.
// Stresses are Kirchhoff stresses τ = J σ, what the MLS-MPM force needs (docs/equations.md §9).
#pragma once
#include <cmath>

#include "core/types.hpp"
#include "sph/equation_of_state.hpp"

namespace sc::mpm {

/// Elastic and frictional constants of the sand, SI units.
struct SandModel {
  double mu = 0.0;      ///< Lamé shear modulus μ [Pa]
  double lambda = 0.0;  ///< Lamé's first parameter λ [Pa]
  double alpha = 0.0;   ///< Drucker-Prager cone slope α: ‖τ̂‖_F ≤ −α tr τ (cone_slope)
  double cot_phi = 0.0; ///< cot φ, the apex shift per unit cohesion
  bool volume_correction = true;

  /// From Young's modulus E, Poisson's ratio ν and the friction angle φ [deg], in D dimensions.
  /// [Klár 2016: Lamé parameters]
  static SandModel from(int dim, double youngs, double poisson, double friction_angle_deg, bool volume_correction);
};

/// The slope α of the Drucker-Prager cone ‖τ̂‖_F ≤ −α tr τ for friction angle φ. In 3-D, Klár et
/// al.'s cone through the Mohr-Coulomb pyramid's compression corners, α = √(2/3) 2 sin φ/(3 − sin φ)
/// [Klár 2016: cone slope α]. In 2-D, with principal stresses σ1, σ2, ‖τ̂‖_F = |σ1 − σ2|/√2, so
/// α = sin φ/√2 is Mohr-Coulomb's |σ1 − σ2| ≤ −sin φ (σ1 + σ2) exactly (the 3-D slope would
/// give the plane a friction angle some degrees lower than φ).
double cone_slope(int dim, double friction_angle_deg);

/// The Kirchhoff stress of the Hencky (St. Venant-Kirchhoff in log strain) energy
/// ψ = μ tr(ε²) + (λ/2) (tr ε)² at the elastic deformation gradient F^E = U Σ Vᵀ, ε = log Σ:
/// τ = U (2μ ε + λ tr(ε) 𝟙) Uᵀ. [Klár 2016: Hencky energy, eq. for τ]
template <int D>
Mat<D> hencky_kirchhoff(const Mat<D>& Fe, const SandModel& m);

/// The Kirchhoff stress of the log strain ε (principal values) in the principal frame U.
template <int D>
Mat<D> hencky_kirchhoff(const Mat<D>& U, const Vec<D>& eps, const SandModel& m);

/// The result of the plastic projection: the admissible log strain and the volume correction left.
template <int D>
struct Projection {
  Vec<D> eps;
  double volume_correction = 0.0;
};

/// Drucker-Prager return mapping of the trial log strain ε (principal values) of a sand particle
/// with cohesion c [Pa] and stored volume correction v_c:
///  - the trial is first dilated by v_c/d per axis, the plastic volume gain the particle owes back
///    [Tampubolon 2017: eq. 27, volume-corrected trial];
///  - cohesion moves the cone's apex to the isotropic tension c cot φ, the Mohr-Coulomb reading of
///    c, i.e. to the log strain e_c = c cot φ / (2μ + dλ) on each axis [Tampubolon 2017: cohesion];
///  - relative to the apex, a trial under expansion goes to the apex, one outside the cone in
///    compression is moved along its deviator onto the cone by δγ = ‖ε̂‖ + α (dλ + 2μ)/(2μ) tr ε,
///    one inside stays [Klár 2016: return mapping, cases I-III];
///  - the new correction is v_c + tr ε_trial − tr ε_new: the volume the projection added, stored
///    so that a later compression first gives it back [Tampubolon 2017: eq. 26]. Without the
///    correction (m.volume_correction false) it stays 0.
template <int D>
Projection<D> project_drucker_prager(const Vec<D>& eps, double cohesion, double volume_correction, const SandModel& m);

/// Sand particle cohesion c = c0 (1 − s) at saturation s in [0, 1]. [Tampubolon 2017: cohesion c(φ)]
inline double wet_cohesion(double dry_cohesion, double saturation) { return dry_cohesion * (1.0 - saturation); }

/// The Kirchhoff stress of water at volume ratio J: τ = −J p(ρ0/J) 𝟙 with the case's equation of
/// state (Tait: p = B ((ρ/ρ0)^γ − 1) = B (J^−γ − 1)). [Tampubolon 2017: weakly compressible water]
template <int D>
Mat<D> water_kirchhoff(double J, double rho0, const EquationOfState& eos) {
  return -J * eos.pressure(rho0 / J, rho0) * Mat<D>::Identity();
}

}  // namespace sc::mpm
