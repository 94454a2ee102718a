// Equations of state: pressure from density for weakly compressible SPH.
#pragma once
#include <algorithm>
#include <cmath>
#include <string>

namespace sc {

/// Tait equation [thesis eq. 7] (Becker & Teschner 2007): P = B((ρ/ρ0)^γ − 1).
/// Correct as printed. B is derived from the speed of sound by `tait_stiffness`.
inline double tait_pressure(double rho, double rho0, double B, double gamma) {
  return B * (std::pow(rho / rho0, gamma) - 1.0);
}

/// Tait stiffness B = ρ0 c²/γ, so that dP/dρ at ρ0 equals c² (Becker & Teschner 2007).
inline double tait_stiffness(double rho0, double sound_speed, double gamma) {
  return rho0 * sound_speed * sound_speed / gamma;
}

/// Linear state equation (thesis, unnumbered under eq 6; Müller 2003): P = k(ρ/ρ0 − 1), k in Pa.
/// The thesis' "ρ" in this formula is the rest density ρ0.
inline double linear_pressure(double rho, double rho0, double k) { return k * (rho / rho0 - 1.0); }

/// The state equation of a case: kind, speed of sound and exponent, with the option to clamp
/// negative pressures to zero (against the tensile instability at free surfaces).
struct EquationOfState {
  enum class Kind { Linear, Tait };
  Kind kind = Kind::Tait;
  double sound_speed = 20.0;  ///< c [m/s]
  double gamma = 7.0;         ///< Tait exponent [-]
  bool clamp_negative = true;

  /// Pressure [Pa] at density rho for a particle of rest density rho0. With the clamp, a particle
  /// at or below its rest density gets 0 without std::pow (both laws give p <= 0 there, clamped to
  /// +0, so the bits are the same; a NaN density gives 0 either way).
  double pressure(double rho, double rho0) const {
    if (clamp_negative && !(rho > rho0)) return 0.0;
    const double c2 = sound_speed * sound_speed;
    const double p = kind == Kind::Tait ? tait_pressure(rho, rho0, rho0 * c2 / gamma, gamma)
                                        : linear_pressure(rho, rho0, rho0 * c2);
    return clamp_negative ? std::max(0.0, p) : p;
  }
  /// Inverse: the density at which the pressure is p (used for wall particles). p = 0 (most wall
  /// particles, far from the fluid) gives rho0 without std::pow: pow(1, 1/γ) is exactly 1.
  double density(double p, double rho0) const {
    if (p == 0.0) return rho0;
    const double c2 = sound_speed * sound_speed;
    if (kind == Kind::Tait) return rho0 * std::pow(std::max(1e-12, 1.0 + p * gamma / (rho0 * c2)), 1.0 / gamma);
    return rho0 * std::max(1e-12, 1.0 + p / (rho0 * c2));
  }
};

}  // namespace sc
