// Time integration: the symplectic Euler step of free particles against the exact solution of its
// own recurrence (free fall, linear spring), and the rigid-cluster sums [thesis eq. 13]
// [thesis eq. 14] that drive the clusters' motion, under an external load.
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <numeric>
#include <random>

#include "sand/rigid_body.hpp"
#include "simulator/simulator.hpp"
#include "simulator/symplectic_euler.hpp"

using namespace sc;

namespace {

/// One water particle at x0 moving at v0, far from anything else.
ParticleSet<2> lone_particle(const Vec<2>& x0, const Vec<2>& v0) {
  ParticleSet<2> ps;
  const std::size_t i = ps.append();
  ps.m[i] = 0.1;
  ps.h[i] = 0.03;
  ps.rho0[i] = ps.rho[i] = 1000.0;
  ps.x[i] = x0;
  ps.v[i] = v0;
  return ps;
}

/// A fixed step dt in a 20 m domain, no gravity.
SimulationParams free_space(double dt) {
  SimulationParams params;
  params.gravity = {0.0, 0.0};
  params.dt_max = dt;
  params.domain_min = {-10.0, -10.0};
  params.domain_max = {10.0, 10.0};
  return params;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(integrator)

BOOST_AUTO_TEST_CASE(free_fall_matches_the_discrete_solution) {
  // A lone particle in the simulator under gravity g with a fixed step Δt: the scheme's recurrence
  // v_{k+1} = v_k + g Δt, x_{k+1} = x_k + Δt v_{k+1} has the closed form v_n = v_0 + n g Δt,
  // x_n = x_0 + n Δt v_0 + g Δt² n(n + 1)/2 (explicit Euler would give n(n − 1)/2). To round-off.
  const Vec<2> x0(0.3, 2.0), v0(0.5, 1.5);
  SimulationParams params = free_space(2e-3);
  params.gravity = {0.0, -9.81};
  Simulator<2> sim(lone_particle(x0, v0), params);
  const int n = 400;
  for (int k = 0; k < n; ++k) BOOST_REQUIRE(sim.step() == params.dt_max);
  const double dt = params.dt_max;
  const Vec<2> g(0.0, -9.81);
  const Vec<2> v_exact = v0 + n * dt * g;
  const Vec<2> x_exact = x0 + n * dt * v0 + (dt * dt * n * (n + 1) / 2.0) * g;
  BOOST_TEST((sim.particles().v[0] - v_exact).norm() <= 1e-12 * v_exact.norm());
  BOOST_TEST((sim.particles().x[0] - x_exact).norm() <= 1e-12 * x_exact.norm());
}

BOOST_AUTO_TEST_CASE(start_up_relaxation_damps_until_relax_until_and_not_after) {
  // The simulator's initial relaxation (SimulationParams::relax_until, relax_rate): a lone particle
  // without gravity moves at v0; each step that starts before relax_until multiplies its velocity by
  // exp(−rate Δt), each later step leaves it. relax_until = 0.0305 s with Δt = 1 ms: steps 0 .. 30
  // start before it (31 damped steps), steps 31 .. 59 after it. To round-off.
  const Vec<2> v0(0.5, -1.5);
  SimulationParams params = free_space(1e-3);
  params.relax_until = 0.0305;
  params.relax_rate = 20.0;
  Simulator<2> sim(lone_particle(Vec<2>(0.3, 2.0), v0), params);
  const double d = std::exp(-params.relax_rate * params.dt_max);
  for (int k = 0; k < 60; ++k) {
    BOOST_REQUIRE(sim.step() == params.dt_max);
    const Vec<2> expected = std::pow(d, std::min(k + 1, 31)) * v0;
    BOOST_TEST_CONTEXT("after step " << k) {
      BOOST_TEST((sim.particles().v[0] - expected).norm() <= 1e-12 * v0.norm());
    }
  }
}

BOOST_AUTO_TEST_CASE(linear_spring_matches_the_discrete_solution) {
  // A particle on a linear spring F = −k x stepped with symplectic_euler_step: the recurrence
  // (x, v) → (x + Δt v', v' = v − Δt ω² x) has the matrix [[1 − ω²Δt², Δt], [−ω²Δt, 1]] of
  // determinant 1, so x_n = x_0 cos nθ + B sin nθ with cos θ = 1 − ω²Δt²/2 and
  // B = (x_1 − x_0 cos θ)/sin θ, x_1 = (1 − ω²Δt²) x_0 + Δt v_0: the scheme neither gains nor
  // loses amplitude. To round-off over 2000 steps (about 30 periods).
  const double m = 0.2, k = 50.0, omega = std::sqrt(k / m), dt = 0.01;
  const double x0 = 0.05, v0 = -0.3;
  const double theta = std::acos(1.0 - 0.5 * omega * omega * dt * dt);
  const double x1 = (1.0 - omega * omega * dt * dt) * x0 + dt * v0;
  const double B = (x1 - x0 * std::cos(theta)) / std::sin(theta);
  Vec<3> x(x0, 0.0, 0.0), v(v0, 0.0, 0.0);
  double worst = 0.0;
  for (int n = 1; n <= 2000; ++n) {
    symplectic_euler_step<3>(x, v, Vec<3>(-k * x), m, dt, 1.0);
    worst = std::max(worst, std::abs(x[0] - (x0 * std::cos(n * theta) + B * std::sin(n * theta))));
  }
  const double amplitude = std::hypot(x0, B);
  BOOST_TEST(worst <= 1e-11 * amplitude);
  BOOST_TEST(x.tail<2>().norm() == 0.0);
}

BOOST_AUTO_TEST_CASE(start_up_damping_scales_the_new_velocity) {
  // symplectic_euler_step with damping d under a constant force F (a = F/m): the recurrence
  // v_{k+1} = d (v_k + Δt a), x_{k+1} = x_k + Δt v_{k+1} has the closed form v_n = dⁿ v_0 + Δt a S_n
  // with S_n = d + … + dⁿ = d (1 − dⁿ)/(1 − d), and x_n = x_0 + Δt (S_n v_0 + Δt a Σ_{k=1..n} S_k),
  // Σ S_k = d (n − S_n)/(1 − d). To round-off over 500 steps, for d < 1 (damped) and d = 1 (free
  // fall: S_n = n, Σ S_k = n(n + 1)/2).
  const double m = 0.3, dt = 2e-3;
  const Vec<2> F(0.6, -2.943), a = F / m, x0(0.1, 1.0), v0(-0.4, 0.7);
  const int n = 500;
  for (const double d : {0.99, 1.0}) {
    Vec<2> x = x0, v = v0;
    for (int k = 0; k < n; ++k) symplectic_euler_step<2>(x, v, F, m, dt, d);
    const double S = d < 1.0 ? d * (1.0 - std::pow(d, n)) / (1.0 - d) : n;
    const double sum_S = d < 1.0 ? d * (n - S) / (1.0 - d) : n * (n + 1) / 2.0;
    const Vec<2> v_exact = std::pow(d, n) * v0 + dt * S * a;
    const Vec<2> x_exact = x0 + dt * (S * v0 + dt * sum_S * a);
    BOOST_TEST((v - v_exact).norm() <= 1e-12 * v_exact.norm());
    BOOST_TEST((x - x_exact).norm() <= 1e-12 * x_exact.norm());
  }
}

BOOST_AUTO_TEST_CASE(cluster_sums_eqs_13_14_carry_an_external_load) {
  // [thesis eq. 13] [thesis eq. 14] on a random cluster with internal central pair forces, gravity
  // and one external point load P at member q: F_cluster = M g + P and τ_cluster = (x_q − x_cm) × P,
  // to round-off (internal forces and uniform gravity add nothing).
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int n = 25, q = 7;
  VecArrayOf<3> x(n), f(n);
  std::vector<double> m(n);
  const Vec<3> g(0.0, 0.0, -9.81), P(3.0, -1.0, 2.0);
  for (int i = 0; i < n; ++i) {
    x[i] = Vec<3>(u(rng), u(rng), u(rng));
    m[i] = 0.5 + u(rng);
  }
  for (int i = 0; i < n; ++i) {
    f[i] = m[i] * g;
    for (int j = 0; j < n; ++j)
      if (i != j) f[i] += (x[i] - x[j]) * (1.0 / (1.0 + (x[i] - x[j]).norm()));  // central, f_ij = −f_ji
  }
  f[q] += P;
  std::vector<std::size_t> members(n);
  std::iota(members.begin(), members.end(), std::size_t{0});
  const auto [M, c] = mass_and_centre<3>(members, m, x);
  const Vec<3> F = cluster_force<3>(members, f);
  const Vec<3> tau = cluster_torque<3>(members, x, c, f);
  BOOST_TEST((F - (M * g + P)).norm() <= 1e-12 * (M * g + P).norm());
  const Vec<3> tau_exact = (x[q] - c).cross(P);
  BOOST_TEST((tau - tau_exact).norm() <= 1e-12 * tau_exact.norm() * n);
}

BOOST_AUTO_TEST_SUITE_END()
