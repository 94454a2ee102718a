// Green-Ampt ponded infiltration (Green & Ampt 1911; docs/references.md §4) [exact for the sharp-front model].
#pragma once
#include <gsl/gsl_sf_gamma.h>
#include <gsl/gsl_sf_lambert.h>

#include <cmath>

namespace sc::analytic {

/// Cumulative infiltration F(t) [m] into a uniform soil of hydraulic conductivity K [m/s], front
/// suction head psi [m] and fillable porosity dtheta [-], ponded at negligible depth:
///   K t = F − ψΔθ ln(1 + F/(ψΔθ)),  explicitly  F = −ψΔθ (1 + W₋₁(−exp(−1 − K t/(ψΔθ)))).
inline double green_ampt_infiltration(double K, double psi, double dtheta, double t) {
  const double s = psi * dtheta;
  if (t <= 0.0) return 0.0;
  return -s * (1.0 + gsl_sf_lambert_Wm1(-std::exp(-1.0 - K * t / s)));
}

/// Depth of the wetting front z_f = F/Δθ [m].
inline double green_ampt_front_depth(double F, double dtheta) { return F / dtheta; }

/// Infiltration rate dF/dt = K (1 + (ψ + h)Δθ/F) [m/s] under a pond of depth h [m] (h = 0: the
/// classical f = K (1 + ψΔθ/F)); the green_ampt observer integrates it over the measured h(t).
inline double green_ampt_rate(double K, double psi, double dtheta, double F, double pond = 0.0) {
  return K * (1.0 + (psi + pond) * dtheta / F);
}

/// Effective suction head at the front (the capillary drive of Neuman 1976 / Morel-Seytoux &
/// Khanji 1974), ψ = ∫₀^{h_c(0)} k_r dh, for the retention curve of the capillary potential
/// [thesis eq. 23] as a suction head h_c(S) = H_c (1 − S)^α, H_c = k^c/(ρ g), and the relative
/// permeability k_r = S^{β+1} of the upwind diffusion (S^β of eq 29 times the absorbed mass ∝ S):
///   ψ = α H_c B(α, β + 2).
inline double capillary_drive(double Hc, double alpha, double beta) {
  return alpha * Hc * gsl_sf_beta(alpha, beta + 2.0);
}

}  // namespace sc::analytic
