// Equations of state: linear (unnumbered, under eq 6) and Tait [thesis eq. 7].
#include <algorithm>
#include <cmath>

#include <boost/test/unit_test.hpp>

#include "sph/equation_of_state.hpp"

using namespace sc;

BOOST_AUTO_TEST_SUITE(equation_of_state)

BOOST_AUTO_TEST_CASE(tait_thesis_eq_7_rest_slope_and_compression) {
  // [thesis eq. 7] P = B((ρ/ρ0)^γ − 1), B = ρ0 c²/γ.
  const double rho0 = 1000.0, c = 20.0, gamma = 7.0;
  const double B = tait_stiffness(rho0, c, gamma);
  BOOST_TEST(tait_pressure(rho0, rho0, B, gamma) == 0.0);
  const double eps = 1e-6 * rho0;
  const double slope = (tait_pressure(rho0 + eps, rho0, B, gamma) - tait_pressure(rho0 - eps, rho0, B, gamma)) / (2 * eps);
  BOOST_TEST(slope == c * c, boost::test_tools::tolerance(1e-8));
  // 1 % compression: P ≈ Bγ·0.01 to first order (second-order term γ(γ−1)/2·1e-4 ≈ 2 %).
  BOOST_TEST(tait_pressure(1.01 * rho0, rho0, B, gamma) == B * gamma * 0.01, boost::test_tools::tolerance(0.04));
}

BOOST_AUTO_TEST_CASE(linear_state_equation) {
  BOOST_TEST(linear_pressure(1000.0, 1000.0, 5e4) == 0.0);
  BOOST_TEST(linear_pressure(1010.0, 1000.0, 5e4) == 500.0, boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(inverse_and_clamping) {
  EquationOfState eos;
  eos.sound_speed = 15.0;
  for (auto kind : {EquationOfState::Kind::Tait, EquationOfState::Kind::Linear}) {
    eos.kind = kind;
    eos.clamp_negative = false;
    for (double rho : {990.0, 1000.0, 1023.0})
      BOOST_TEST(eos.density(eos.pressure(rho, 1000.0), 1000.0) == rho, boost::test_tools::tolerance(1e-12));
    eos.clamp_negative = true;
    BOOST_TEST(eos.pressure(990.0, 1000.0) == 0.0);
  }
}

BOOST_AUTO_TEST_CASE(shortcuts_without_pow_have_the_bits_of_the_full_laws) {
  // pressure() returns +0 at or below rest density with the clamp, density() returns rho0 at p = 0:
  // the same bits as evaluating the laws with std::pow.
  EquationOfState eos;
  eos.sound_speed = 10.0;
  const double rho0 = 1000.0, c2 = eos.sound_speed * eos.sound_speed;
  for (const double rho : {0.0, 500.0, 999.9999999, 1000.0}) {
    const double full = std::max(0.0, tait_pressure(rho, rho0, rho0 * c2 / eos.gamma, eos.gamma));
    const double p = eos.pressure(rho, rho0);
    BOOST_TEST(p == full);
    BOOST_TEST(!std::signbit(p));
  }
  BOOST_TEST(eos.density(0.0, rho0) == rho0 * std::pow(1.0 + 0.0 * eos.gamma / (rho0 * c2), 1.0 / eos.gamma));
  eos.kind = EquationOfState::Kind::Linear;
  BOOST_TEST(eos.density(0.0, rho0) == rho0 * std::max(1e-12, 1.0 + 0.0 / (rho0 * c2)));
}

BOOST_AUTO_TEST_SUITE_END()
