// The torque-free rigid-body reference (reference/analytic/free_rigid_body.hpp) against itself: the
// GSL solution of [Euler 1765: torque-free rigid body] keeps both invariants, and its flip period,
// measured by the sign changes of the intermediate component of ω over several periods, is the
// closed-form period of [Landau & Lifshitz §37: Jacobi elliptic functions] on both sides of the
// separatrix. The rigid_spin observer gates the solver's spinning sand bodies on these references.
#include <boost/test/unit_test.hpp>
#include <cmath>

#include "reference/analytic/free_rigid_body.hpp"

using namespace sc::analytic;

namespace {

/// Moments of the lattice box of the rigid_spin_3d case, in units of its smallest (1 : 2 : 2.6).
const Vec3 kMoments{1.0, 2.0256, 2.641};

/// Samples every `step` seconds from 0 to `end`.
std::vector<double> sample_times(double end, double step) {
  std::vector<double> t;
  for (int n = 0; n * step <= end; ++n) t.push_back(n * step);
  return t;
}

/// The period of the intermediate component of ω from its sign changes over `periods` periods of
/// the exact solution, sampled 2000 times per period.
double flip_period_of_ode(const Vec3& omega0, double periods, std::size_t& changes) {
  const double T = torque_free_period(kMoments, omega0);
  const std::vector<double> t = sample_times(periods * T, T / 2000.0);
  const std::vector<Vec3> w = torque_free_omega(kMoments, omega0, t);
  std::vector<double> w2;
  for (const Vec3& s : w) w2.push_back(s[1]);
  const std::vector<double> flips = sign_changes(t, w2);
  changes = flips.size();
  return period_from_sign_changes(flips);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(free_rigid_body)

BOOST_AUTO_TEST_CASE(ode_solution_keeps_energy_and_angular_momentum) {
  // M² = |Iω|² and 2E = ω·Iω are invariants of Euler's equations; rk8pd at 1e-13 keeps them to
  // 1e-11 over 50 time units (about ten flips).
  const Vec3 w0{0.4, 8.0, 0.4};
  const std::vector<double> t = sample_times(50.0, 0.01);
  const std::vector<Vec3> w = torque_free_omega(kMoments, w0, t);
  auto invariants = [](const Vec3& s) {
    double M2 = 0.0, twoE = 0.0;
    for (int k = 0; k < 3; ++k) {
      M2 += kMoments[k] * kMoments[k] * s[k] * s[k];
      twoE += kMoments[k] * s[k] * s[k];
    }
    return std::pair{M2, twoE};
  };
  const auto [M2_0, twoE_0] = invariants(w0);
  double worst = 0.0;
  for (const Vec3& s : w) {
    const auto [M2, twoE] = invariants(s);
    worst = std::max({worst, std::abs(M2 / M2_0 - 1.0), std::abs(twoE / twoE_0 - 1.0)});
  }
  BOOST_TEST_MESSAGE("largest relative invariant error " << worst);
  BOOST_TEST(worst < 1e-11);
  BOOST_TEST(std::abs(w.back()[1] - w0[1]) > 1.0);  // ω changes: the flip is under way
}

BOOST_AUTO_TEST_CASE(flip_period_of_the_ode_is_the_elliptic_integral_period) {
  // ω0 near the intermediate axis, tilted towards the smallest (M² > 2E I_2) and towards the largest
  // moment (M² < 2E I_2): five periods give ten sign changes, whose mean interval is half the
  // closed-form period to 1e-8.
  for (const Vec3& w0 : {Vec3{0.5, 8.0, 0.3}, Vec3{0.3, 8.0, 0.5}}) {
    std::size_t changes = 0;
    const double T = torque_free_period(kMoments, w0), T_ode = flip_period_of_ode(w0, 5.0, changes);
    BOOST_TEST_MESSAGE("T " << T << " s, from " << changes << " sign changes " << T_ode << " s");
    BOOST_TEST(changes >= 9u);
    BOOST_TEST(std::abs(T_ode / T - 1.0) < 1e-8);
  }
}

BOOST_AUTO_TEST_CASE(period_is_infinite_on_the_separatrix_and_absent_without_sign_changes) {
  // Spin exactly about the intermediate axis: M² = 2E I_2, the flip never comes. A curve with one
  // sign change has no period.
  BOOST_TEST(std::isinf(torque_free_period(kMoments, Vec3{0.0, 8.0, 0.0})));
  BOOST_TEST(std::isnan(period_from_sign_changes({1.0})));
}

BOOST_AUTO_TEST_SUITE_END()
