// The torque-free rigid body (Euler's equations; Landau & Lifshitz, Mechanics §37; docs/references.md
// §6) [exact]: an accurate numerical solution of Euler's equations and the closed-form period of
// ω(t) in Jacobi elliptic functions. The rigid_spin observer compares the solver's spinning sand
// bodies with both; tests/test_free_rigid_body.cpp checks that the two agree.
#pragma once
#include <gsl/gsl_errno.h>
#include <gsl/gsl_mode.h>
#include <gsl/gsl_odeiv2.h>
#include <gsl/gsl_sf_ellint.h>

#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace sc::analytic {

using Vec3 = std::array<double, 3>;

/// Right-hand side of [Euler 1765: torque-free rigid body] in the principal frame of the body,
/// I_1 ω̇_1 = (I_2 − I_3) ω_2 ω_3 and cyclic; `params` points at the principal moments I.
inline int euler_free_body_rhs(double, const double w[], double dwdt[], void* params) {
  const double* I = static_cast<const double*>(params);
  dwdt[0] = (I[1] - I[2]) * w[1] * w[2] / I[0];
  dwdt[1] = (I[2] - I[0]) * w[2] * w[0] / I[1];
  dwdt[2] = (I[0] - I[1]) * w[0] * w[1] / I[2];
  return GSL_SUCCESS;
}

/// ω(t) in the principal frame at each of `times` (non-decreasing, from t = 0) of the body with
/// principal moments I that spins at ω0 at t = 0: [Euler 1765: torque-free rigid body] integrated by
/// GSL's embedded Runge-Kutta-Prince-Dormand (8, 9) at relative and absolute tolerance 1e-13
/// (per unit |ω0|), far below any error of a simulation it is compared with.
inline std::vector<Vec3> torque_free_omega(const Vec3& I, const Vec3& omega0, const std::vector<double>& times) {
  Vec3 moments = I;
  gsl_odeiv2_system sys{euler_free_body_rhs, nullptr, 3, moments.data()};
  const double scale = std::sqrt(omega0[0] * omega0[0] + omega0[1] * omega0[1] + omega0[2] * omega0[2]);
  gsl_odeiv2_driver* driver = gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, 1e-3 / scale, 1e-13 * scale, 1e-13);
  std::vector<Vec3> out;
  out.reserve(times.size());
  double t = 0.0;
  Vec3 w = omega0;
  for (const double target : times) {
    if (target > t && gsl_odeiv2_driver_apply(driver, &t, target, w.data()) != GSL_SUCCESS) {
      gsl_odeiv2_driver_free(driver);
      throw std::runtime_error("torque_free_omega: the GSL integrator failed");
    }
    out.push_back(w);
  }
  gsl_odeiv2_driver_free(driver);
  return out;
}

/// Period of ω(t) of the torque-free body with principal moments I_1 < I_2 < I_3 that spins at ω0
/// (principal frame), [Landau & Lifshitz §37: Jacobi elliptic functions]: with M² = |Iω|² and
/// 2E = ω·Iω, for M² > 2E I_2
///   T = 4 K(k) √(I_1 I_2 I_3 / ((I_3 − I_2)(M² − 2E I_1))),  k² = (I_2 − I_1)(2E I_3 − M²) / ((I_3 − I_2)(M² − 2E I_1)),
/// and with I_1 and I_3 exchanged for M² < 2E I_2. Near the intermediate axis this is the period
/// of its flip: the intermediate component of ω changes sign twice per period. Infinite on the
/// separatrix (M² = 2E I_2), where the flip takes forever.
inline double torque_free_period(const Vec3& I, const Vec3& omega0) {
  double M2 = 0.0, twoE = 0.0;
  for (int k = 0; k < 3; ++k) {
    M2 += I[k] * I[k] * omega0[k] * omega0[k];
    twoE += I[k] * omega0[k] * omega0[k];
  }
  if (M2 == twoE * I[1]) return INFINITY;
  const bool about_smallest = M2 > twoE * I[1];
  const double a = about_smallest ? I[0] : I[2], c = about_smallest ? I[2] : I[0];
  const double k2 = (I[1] - a) * (twoE * c - M2) / ((c - I[1]) * (M2 - twoE * a));
  if (!(k2 < 1.0)) return INFINITY;
  return 4.0 * gsl_sf_ellint_Kcomp(std::sqrt(k2), GSL_PREC_DOUBLE) * std::sqrt(I[0] * I[1] * I[2] / ((c - I[1]) * (M2 - twoE * a)));
}

/// Times where the sampled curve y(t) changes sign, each interpolated linearly between its two
/// samples (at a zero of a Jacobi sn, an inflection point, the error is of third order in the
/// sample step).
inline std::vector<double> sign_changes(const std::vector<double>& t, const std::vector<double>& y) {
  std::vector<double> out;
  for (std::size_t n = 1; n < y.size(); ++n)
    if ((y[n] < 0.0) != (y[n - 1] < 0.0)) out.push_back(t[n - 1] + (t[n] - t[n - 1]) * y[n - 1] / (y[n - 1] - y[n]));
  return out;
}

/// The period of a curve that changes sign twice per period, from its sign changes: twice their
/// mean interval; NaN with fewer than two.
inline double period_from_sign_changes(const std::vector<double>& changes) {
  if (changes.size() < 2) return NAN;
  return 2.0 * (changes.back() - changes.front()) / static_cast<double>(changes.size() - 1);
}

}  // namespace sc::analytic
