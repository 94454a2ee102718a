// Collision of particles with the box tank's walls (Müller, Charypar & Gross 2003: collision
// detection and response at container walls; perfectly inelastic, slip or no-slip per side), and
// the pressure of the wall particles (boundary/wall_pressure.hpp).
#include <random>

#include <boost/test/unit_test.hpp>

#include "boundary/wall_collision.hpp"
#include "boundary/wall_pressure.hpp"
#include "simulator/simulator.hpp"

using namespace sc;

namespace {

/// A 1 m x 1 m tank: slip side walls, a no-slip floor, an open top; walls 0.02 m thick.
TankSpec open_tank() {
  TankSpec t;
  t.min = {0.0, 0.0};
  t.max = {1.0, 1.0};
  t.rules[TankSpec::side_index(0, -1)] = WallRule::Slip;
  t.rules[TankSpec::side_index(0, 1)] = WallRule::Slip;
  t.rules[TankSpec::side_index(1, -1)] = WallRule::NoSlip;
  t.rules[TankSpec::side_index(1, 1)] = WallRule::Open;
  return t;
}

/// One water particle at x with velocity v, moved by one step dt of free flight; returns the set and
/// its position before the move in `start`.
ParticleSet<2> moved_particle(const Vec<2>& x, const Vec<2>& v, double dt, ParticleSet<2>::VecArray& start) {
  ParticleSet<2> ps;
  const std::size_t i = ps.append();
  ps.x[i] = x;
  ps.v[i] = v;
  ps.m[i] = 1e-3;
  ps.h[i] = 0.02;
  ps.rho0[i] = ps.rho[i] = 1000.0;
  start = ps.x;
  ps.x[i] += dt * v;
  return ps;
}

double kinetic_energy(const ParticleSet<2>& ps) { return 0.5 * ps.m[0] * ps.v[0].squaredNorm(); }

/// Appends a particle of the phase at x with support h and density rho, pressure p.
std::size_t add_particle(ParticleSet<2>& ps, Phase phase, const Vec<2>& x, double h, double rho, double p) {
  const std::size_t i = ps.append();
  ps.phase[i] = static_cast<std::uint8_t>(phase);
  ps.x[i] = x;
  ps.h[i] = h;
  ps.m[i] = 1e-3;
  ps.rho0[i] = 1000.0;
  ps.rho[i] = rho;
  ps.p[i] = p;
  return i;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(wall_collision)

BOOST_AUTO_TEST_CASE(slip_wall_stops_the_normal_velocity_and_keeps_the_tangential) {
  // A particle 1 mm from the x+ wall at 7 m/s (a splash speed of the thesis scenes) crosses it
  // within the step; it ends on the wall with v_n = 0 and its tangential velocity unchanged.
  const auto walls = TankWalls<2>::from_tank(open_tank(), 0.02);
  ParticleSet<2>::VecArray start;
  ParticleSet<2> ps = moved_particle(Vec<2>(0.999, 0.5), Vec<2>(7.0, -1.5), 0.001, start);
  const double e0 = kinetic_energy(ps);
  BOOST_TEST(collide_with_tank(ps, walls, start) == 1);
  BOOST_TEST(ps.x[0][0] == 1.0);
  BOOST_TEST(ps.x[0][1] == 0.5 - 0.0015, boost::test_tools::tolerance(1e-15));  // tangential motion kept
  BOOST_TEST(ps.v[0][0] == 0.0);
  BOOST_TEST(ps.v[0][1] == -1.5);
  BOOST_TEST(kinetic_energy(ps) < e0);
}

BOOST_AUTO_TEST_CASE(no_slip_floor_brings_the_particle_to_rest_on_it) {
  const auto walls = TankWalls<2>::from_tank(open_tank(), 0.02);
  ParticleSet<2>::VecArray start;
  ParticleSet<2> ps = moved_particle(Vec<2>(0.3, 0.002), Vec<2>(3.0, -4.0), 0.001, start);
  BOOST_TEST(collide_with_tank(ps, walls, start) == 1);
  BOOST_TEST(ps.x[0][1] == 0.0);
  BOOST_TEST(ps.v[0].norm() == 0.0);
  // An inward velocity is the particle's own: the collision rule never touches it.
  BOOST_TEST((wall_collision_velocity<2>(Vec<2>(3.0, 4.0), Vec<2>(0.0, -1.0), true) - Vec<2>(0.0, 4.0)).norm() == 0.0);
  BOOST_TEST((wall_collision_velocity<2>(Vec<2>(3.0, 4.0), Vec<2>(0.0, -1.0), false) - Vec<2>(3.0, 4.0)).norm() == 0.0);
}

BOOST_AUTO_TEST_CASE(particle_driven_into_a_corner_ends_in_the_corner) {
  const auto walls = TankWalls<2>::from_tank(open_tank(), 0.02);
  ParticleSet<2>::VecArray start;
  ParticleSet<2> ps = moved_particle(Vec<2>(0.998, 0.001), Vec<2>(5.0, -5.0), 0.001, start);
  BOOST_TEST(collide_with_tank(ps, walls, start) == 1);
  BOOST_TEST((ps.x[0] - Vec<2>(1.0, 0.0)).norm() == 0.0);
  BOOST_TEST(ps.v[0].norm() == 0.0);
}

BOOST_AUTO_TEST_CASE(particle_created_inside_the_floor_layers_is_put_on_the_floor) {
  // Water the porous flow emits below a sand grain resting on the floor can start inside the wall's
  // layers; it is put on the floor, not left to fall out of the tank.
  const auto walls = TankWalls<2>::from_tank(open_tank(), 0.02);
  ParticleSet<2>::VecArray start;
  ParticleSet<2> ps = moved_particle(Vec<2>(0.4, -0.008), Vec<2>(0.5, -2.0), 0.001, start);
  BOOST_TEST(collide_with_tank(ps, walls, start) == 1);
  BOOST_TEST((ps.x[0] - Vec<2>(0.4005, 0.0)).norm() <= 1e-15);
  BOOST_TEST(ps.v[0].norm() == 0.0);
}

BOOST_AUTO_TEST_CASE(particle_created_inside_the_floor_layers_and_driven_through_them_is_put_on_the_floor) {
  // Water emitted 8.1 mm deep into the floor's 20 mm layers is driven by the wall and the sand above
  // to 21.9 mm deep in its first step, behind the layers; it is put on the floor all the same, not
  // left to fall out of the domain.
  const auto walls = TankWalls<2>::from_tank(open_tank(), 0.02);
  ParticleSet<2>::VecArray start;
  ParticleSet<2> ps = moved_particle(Vec<2>(0.23, -0.0081), Vec<2>(0.4, -13.8), 0.001, start);
  BOOST_TEST(ps.x[0][1] < -0.02);
  BOOST_TEST(collide_with_tank(ps, walls, start) == 1);
  BOOST_TEST((ps.x[0] - Vec<2>(0.2304, 0.0)).norm() <= 1e-15);
  BOOST_TEST(ps.v[0].norm() == 0.0);
}

BOOST_AUTO_TEST_CASE(particle_over_the_rim_of_an_open_tank_is_left_alone) {
  // The x+ wall ends at the rim y = 1 (the top is open): a splash above it crosses the plane freely,
  // and so does a particle already outside (it went over the rim earlier).
  const auto walls = TankWalls<2>::from_tank(open_tank(), 0.02);
  ParticleSet<2>::VecArray start;
  ParticleSet<2> over = moved_particle(Vec<2>(0.999, 1.05), Vec<2>(7.0, 0.0), 0.001, start);
  BOOST_TEST(collide_with_tank(over, walls, start) == 0);
  BOOST_TEST(over.x[0][0] == 0.999 + 0.007, boost::test_tools::tolerance(1e-15));
  ParticleSet<2> outside = moved_particle(Vec<2>(1.05, 0.5), Vec<2>(-1.0, -1.0), 0.001, start);
  BOOST_TEST(collide_with_tank(outside, walls, start) == 0);
}

BOOST_AUTO_TEST_CASE(particle_crossing_a_side_wall_below_the_rim_is_stopped_though_it_ends_above) {
  // From (0.995, 0.990) at (10, 15) m/s for 1 ms the particle crosses the x+ wall's plane halfway,
  // at y = 0.9975, below the rim (y = 1), and would end at (1.005, 1.005), above it: the crossing
  // point, not the end point, decides. It is put on the wall (slip: the normal velocity stops).
  const auto walls = TankWalls<2>::from_tank(open_tank(), 0.02);
  ParticleSet<2>::VecArray start;
  ParticleSet<2> ps = moved_particle(Vec<2>(0.995, 0.990), Vec<2>(10.0, 15.0), 0.001, start);
  BOOST_TEST(ps.x[0][1] > 1.0);
  BOOST_TEST(collide_with_tank(ps, walls, start) == 1);
  BOOST_TEST(ps.x[0][0] == 1.0);
  BOOST_TEST(ps.v[0][0] == 0.0);
  BOOST_TEST(ps.v[0][1] == 15.0);
}

BOOST_AUTO_TEST_CASE(thrown_particle_never_leaves_a_slip_box_and_only_loses_energy) {
  // A lone water particle (no wall particles: the collision alone holds it) thrown at 20 m/s down and
  // sideways in a 2-D tank with slip walls under gravity: at every step it is inside the tank, its
  // mechanical energy ½ m v² + m g y never exceeds the start value (the inelastic collisions only
  // remove energy; the lift onto the floor, m g δ with δ ≤ v_n Δt, is paid by the removed ½ m v_n²),
  // and it ends at rest in the floor's corner x = 1, y = 0.
  ParticleSet<2>::VecArray start;
  const ParticleSet<2> ps = moved_particle(Vec<2>(0.5, 0.5), Vec<2>(12.0, -16.0), 0.0, start);
  SimulationParams params;
  params.gravity = {0.0, -9.81};
  params.domain_min = {-0.1, -0.1};
  params.domain_max = {1.1, 2.0};
  TankSpec tank = open_tank();
  tank.rules[TankSpec::side_index(1, -1)] = WallRule::Slip;
  tank.collision = true;
  params.tank = tank;
  params.tank_wall_thickness = 0.02;
  Simulator<2> sim(ps, params);
  const auto energy = [&] {
    const auto& p = sim.particles();
    return 0.5 * p.m[0] * p.v[0].squaredNorm() + p.m[0] * 9.81 * p.x[0][1];
  };
  const double e0 = energy();
  bool inside = true, bounded = true;
  for (int s = 0; s < 500; ++s) {
    sim.step();
    const Vec<2>& x = sim.particles().x[0];
    inside = inside && x[0] >= 0.0 && x[0] <= 1.0 && x[1] >= 0.0;
    bounded = bounded && energy() <= e0;
  }
  BOOST_TEST(inside);
  BOOST_TEST(bounded);
  BOOST_TEST((sim.particles().x[0] - Vec<2>(1.0, 0.0)).norm() == 0.0);
  BOOST_TEST(sim.particles().v[0].norm() == 0.0);
}

// p_w = Σ_f (p_f + ρ_f g·(x_w − x_f)) W_wf / Σ_f W_wf: each term is the pressure a hydrostatic
// field has at the wall particle, so a water column at rest gives its own pressure there exactly,
// whatever the weights. A wall particle below the water (gravity pulls towards it) gets more than
// any water particle has.
BOOST_AUTO_TEST_CASE(wall_pressure_continues_a_hydrostatic_field_exactly) {
  constexpr double h = 0.04, rho = 1000.0, g = 9.81, top = 0.3;
  ParticleSet<2> ps;
  const std::size_t wall = add_particle(ps, Phase::Boundary, Vec<2>(0.1, 0.1), h, rho, 0.0);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.9 * h / std::sqrt(2.0), 0.9 * h / std::sqrt(2.0));
  double p_max = 0.0;
  for (int k = 0; k < 12; ++k) {
    const Vec<2> x(0.1 + u(rng), 0.1 + 0.01 + std::abs(u(rng)));
    p_max = std::max(p_max, rho * g * (top - x[1]));
    add_particle(ps, Phase::Water, x, h, rho, rho * g * (top - x[1]));
  }
  add_particle(ps, Phase::Boundary, Vec<2>(0.5, 0.1), h, rho, 123.0);  // no water within reach
  NeighbourGrid<2> nb;
  nb.rebuild(ps);
  EquationOfState eos;
  eos.sound_speed = 20.0;
  extrapolate_wall_pressure(ps, nb, Vec<2>(0.0, -g), eos);
  const double expected = rho * g * (top - 0.1);
  BOOST_TEST(ps.p[wall] > p_max);
  BOOST_TEST(ps.p[wall] == expected, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(ps.rho[wall] == eos.density(expected, rho), boost::test_tools::tolerance(1e-12));
  BOOST_TEST(ps.p[ps.size() - 1] == 0.0);
}

// Without gravity the wall particle takes the Shepard mean of its neighbours' pressures with the
// poly6 weights of its own support, W ∝ (h² − r²)³: here two water particles at 0.3 h and 0.7 h.
// A negative mean is clamped to zero when the state equation clamps.
BOOST_AUTO_TEST_CASE(wall_pressure_is_the_poly6_weighted_mean_of_the_water_near_it) {
  constexpr double h = 0.05, rho = 1000.0;
  const auto scene = [&](double p1, double p2) {
    ParticleSet<2> ps;
    add_particle(ps, Phase::Boundary, Vec<2>(0.2, 0.2), h, rho, 0.0);
    add_particle(ps, Phase::Water, Vec<2>(0.2 + 0.3 * h, 0.2), 0.6 * h, rho, p1);  // its own support smaller
    add_particle(ps, Phase::Water, Vec<2>(0.2, 0.2 + 0.7 * h), 0.6 * h, rho, p2);
    return ps;
  };
  const auto weight = [&](double r) { return std::pow(h * h - r * r, 3); };
  const double w1 = weight(0.3 * h), w2 = weight(0.7 * h);
  EquationOfState eos;
  eos.sound_speed = 20.0;
  ParticleSet<2> ps = scene(1000.0, 3000.0);
  NeighbourGrid<2> nb;
  nb.rebuild(ps);
  extrapolate_wall_pressure(ps, nb, Vec<2>(Vec<2>::Zero()), eos);
  BOOST_TEST(ps.p[0] == (1000.0 * w1 + 3000.0 * w2) / (w1 + w2), boost::test_tools::tolerance(1e-12));
  eos.clamp_negative = true;
  ps = scene(-1000.0, -3000.0);
  nb.rebuild(ps);
  extrapolate_wall_pressure(ps, nb, Vec<2>(Vec<2>::Zero()), eos);
  BOOST_TEST(ps.p[0] == 0.0);
  BOOST_TEST(ps.rho[0] == rho);
  eos.clamp_negative = false;
  ps = scene(-1000.0, -3000.0);
  nb.rebuild(ps);
  extrapolate_wall_pressure(ps, nb, Vec<2>(Vec<2>::Zero()), eos);
  BOOST_TEST(ps.p[0] == -(1000.0 * w1 + 3000.0 * w2) / (w1 + w2), boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_SUITE_END()
