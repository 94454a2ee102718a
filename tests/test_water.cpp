// Water physics: density [thesis eq. 6], interpolation [thesis eq. 1], pressure force
// [thesis eq. 4], viscosity [thesis eq. 5], surface tension, and the momentum balance
// [thesis eq. 2] / [thesis eq. 3] (a = F/m).
#include <boost/test/unit_test.hpp>
#include <random>

#include "scene/scene_builder.hpp"
#include "simulator/simulator.hpp"
#include "sph/density.hpp"
#include "sph/gradient_correction.hpp"
#include "water/pressure_force.hpp"
#include "water/surface_tension.hpp"
#include "water/viscosity_force.hpp"
#include "water/water_forces.hpp"
#include "support/lattice.hpp"

using namespace sc;

namespace {

/// A square lattice of n x n water particles at spacing dx with calibrated mass and support ratio 3.
ParticleSet<2> lattice(int n, double dx, double rho0 = 1000.0) {
  return test::square_lattice(n, dx, 3.0, rho0, Phase::Water);
}

std::size_t centre_index(int n) { return static_cast<std::size_t>((n / 2) * n + n / 2); }

/// Random particles with unequal radii, masses, densities, pressures and velocities.
ParticleSet<3> random_cloud(unsigned seed, int n) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  ParticleSet<3> ps;
  for (int k = 0; k < n; ++k) {
    const std::size_t i = ps.append();
    ps.x[i] = Vec<3>(u(rng), u(rng), u(rng)) * 0.3;
    ps.v[i] = Vec<3>(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
    ps.h[i] = 0.06 + 0.06 * u(rng);
    ps.m[i] = 0.01 + 0.02 * u(rng);
    ps.rho[i] = 900.0 + 200.0 * u(rng);
    ps.rho0[i] = 1000.0;
    ps.p[i] = 5000.0 * u(rng);
  }
  return ps;
}

/// Sum and summed magnitude of a pair force f(i, j, d = x_i − x_j) over all neighbour pairs i ≠ j.
template <class PairForce>
std::pair<Vec<3>, double> pair_force_sum(const ParticleSet<3>& ps, PairForce&& f) {
  NeighbourGrid<3> nb;
  nb.rebuild(ps);
  Vec<3> total = Vec<3>::Zero();
  double scale = 0.0;
  for (std::size_t i = 0; i < ps.size(); ++i)
    for (auto j : nb.of(i)) {
      if (j == i) continue;
      const Vec<3> fij = f(i, j, Vec<3>(ps.x[i] - ps.x[j]));
      total += fij;
      scale += fij.norm();
    }
  return {total, scale};
}

}  // namespace

BOOST_AUTO_TEST_SUITE(water)

BOOST_AUTO_TEST_CASE(density_eq_6_of_a_lattice_is_the_rest_density) {
  // [thesis eq. 6] with the calibrated lattice mass: interior density equals ρ0 (to round-off).
  ParticleSet<2> ps = lattice(15, 0.01);
  NeighbourGrid<2> nb;
  nb.rebuild(ps);
  compute_density(ps, nb, kernel::DensityKernel::Spiky);
  BOOST_TEST(ps.rho[centre_index(15)] == 1000.0, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(ps.rho[0] < 800.0);  // a corner lacks neighbours
}

BOOST_AUTO_TEST_CASE(density_eq_6_of_water_beside_sand_counts_the_sand_as_water) {
  // [thesis eq. 6] at a water-sand interface (neighbour_density_mass): with the left half of a
  // lattice turned into sand of twice the rest density (and twice the lattice mass), a water
  // particle on the interface reads exactly the density of the all-water lattice when sand counts
  // with its volume at ρ^f; with sand's own mass it reads far more (the Tait blow-up it caused).
  ParticleSet<2> ps = lattice(15, 0.01);
  NeighbourGrid<2> nb;
  nb.rebuild(ps);
  compute_density(ps, nb, kernel::DensityKernel::Spiky, 1000.0);
  const std::size_t c = centre_index(15);
  const double all_water = ps.rho[c];
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps.x[i][0] >= ps.x[c][0] - 0.005) continue;
    ps.phase[i] = static_cast<std::uint8_t>(Phase::Sand);
    ps.m[i] *= 2.0;
    ps.rho0[i] = 2000.0;
  }
  compute_density(ps, nb, kernel::DensityKernel::Spiky, 1000.0);
  BOOST_TEST(ps.rho[c] == all_water, boost::test_tools::tolerance(1e-12));
  compute_density(ps, nb, kernel::DensityKernel::Spiky);
  BOOST_TEST(ps.rho[c] > 1.05 * all_water);
}

BOOST_AUTO_TEST_CASE(interpolation_eq_1_of_constant_and_linear_fields) {
  // [thesis eq. 1] A(x_i) = Σ V_j A_j W_j: a constant field in the interior of a lattice is exact
  // (to the kernel's lattice error), and the Shepard-normalised linear field is exact.
  ParticleSet<2> ps = lattice(15, 0.01);
  NeighbourGrid<2> nb;
  nb.rebuild(ps);
  compute_density(ps, nb, kernel::DensityKernel::Poly6);
  std::vector<double> one(ps.size(), 1.0), lin(ps.size());
  for (std::size_t i = 0; i < ps.size(); ++i) lin[i] = 3.0 * ps.x[i][0] - 2.0 * ps.x[i][1];
  const std::size_t c = centre_index(15);
  const double shepard = interpolate(ps, nb, std::span<const double>(one), c);
  BOOST_TEST(shepard == 1.0, boost::test_tools::tolerance(0.03));
  BOOST_TEST(interpolate(ps, nb, std::span<const double>(lin), c) / shepard == lin[c], boost::test_tools::tolerance(1e-9));
}

BOOST_AUTO_TEST_CASE(pressure_force_eq_4_conserves_momentum_with_unequal_radii) {
  // [thesis eq. 4]: f_ij = −f_ji for every pair, so the forces sum to zero.
  const ParticleSet<3> ps = random_cloud(7, 300);
  const auto [total, scale] = pair_force_sum(ps, [&](std::size_t i, std::size_t j, const Vec<3>& d) {
    return pressure_pair_force<3>(ps.volume(i), ps.volume(j), ps.p[i], ps.p[j], d, d.norm(), ps.h[i], ps.h[j]);
  });
  BOOST_TEST(scale > 0.0);
  BOOST_TEST(total.norm() <= 1e-13 * scale);
}

BOOST_AUTO_TEST_CASE(pressure_force_eq_4_pushes_apart) {
  const Vec<2> d(-0.01, 0.0);  // x_i − x_j: j lies at +x
  const Vec<2> f = pressure_pair_force<2>(1e-4, 1e-4, 100.0, 100.0, d, 0.01, 0.03, 0.02);
  BOOST_TEST(f[0] < 0.0);  // i is pushed away from j
  BOOST_TEST(f[1] == 0.0);
}

BOOST_AUTO_TEST_CASE(pressure_force_reproduces_linear_gradient) {
  // On a lattice with P = a·x, the corrected eq-4 force on an interior particle is −V_i a (the
  // thesis' P_i + P_j form); Müller's (P_i + P_j)/2 gives half of it (EQUATIONS.md eq 4 discussion).
  const int n = 17;
  ParticleSet<2> ps = lattice(n, 0.01);
  const Vec<2> a(3000.0, -9810.0);
  for (std::size_t i = 0; i < ps.size(); ++i) ps.p[i] = 5000.0 + a.dot(ps.x[i]);
  NeighbourGrid<2> nb;
  nb.rebuild(ps);
  MatArray<2> L;
  compute_gradient_corrections(ps, nb, L);
  const std::size_t c = centre_index(n);
  WaterParams params;
  for (bool half : {false, true}) {
    params.mueller_half_pressure = half;
    for (auto& f : ps.force) f.setZero();
    add_water_forces(ps, nb, params, L);
    const Vec<2> expected = -ps.volume(c) * a * (half ? 0.5 : 1.0);
    BOOST_TEST((ps.force[c] - expected).norm() <= 1e-9 * expected.norm());
  }
  params.mueller_half_pressure = false;
  params.gradient_correction = false;  // uncorrected spiky gradient: about 10 % short at h = 3 dx
  for (auto& f : ps.force) f.setZero();
  add_water_forces(ps, nb, params, L);
  const double ratio = ps.force[c].dot(-a) / (ps.volume(c) * a.squaredNorm());
  BOOST_TEST(ratio > 0.85);
  BOOST_TEST(ratio < 0.95);
}

BOOST_AUTO_TEST_CASE(viscosity_eq_5_is_symmetric_and_dissipative) {
  // [thesis eq. 5]: f_ij = −f_ji; zero for uniform motion; opposes the relative velocity.
  const Vec<3> vi(1.0, 0.0, 0.0), vj(-1.0, 0.5, 0.0);
  const Vec<3> fij = viscosity_pair_force<3>(0.1, 1e-6, 2e-6, vi, vj, 0.01, 0.03, 0.02);
  const Vec<3> fji = viscosity_pair_force<3>(0.1, 2e-6, 1e-6, vj, vi, 0.01, 0.02, 0.03);
  BOOST_TEST((fij + fji).norm() == 0.0);
  BOOST_TEST(fij.dot(vi - vj) < 0.0);  // power of the pair force on the relative motion is negative
  BOOST_TEST(viscosity_pair_force<3>(0.1, 1e-6, 1e-6, vi, vi, 0.01, 0.03, 0.03).norm() == 0.0);
}

BOOST_AUTO_TEST_CASE(surface_tension_conserves_momentum_with_unequal_masses) {
  const ParticleSet<3> ps = random_cloud(3, 200);
  const auto [total, scale] = pair_force_sum(ps, [&](std::size_t i, std::size_t j, const Vec<3>& d) {
    return surface_tension_pair_force<3>(2.0, ps.m[i], ps.m[j], d, d.norm(), ps.h[i], ps.h[j]);
  });
  BOOST_TEST(scale > 0.0);
  BOOST_TEST(total.norm() <= 1e-13 * scale);
}

BOOST_AUTO_TEST_CASE(all_water_forces_sum_to_zero) {
  // The assembled pair forces (eq 4 with correction, eq 5, surface tension) between moving
  // particles conserve linear momentum.
  ParticleSet<3> ps = random_cloud(11, 400);
  NeighbourGrid<3> nb;
  nb.rebuild(ps);
  MatArray<3> L;
  compute_gradient_corrections(ps, nb, L);
  WaterParams params;
  params.viscosity = 0.5;
  params.surface_tension = 1.0;
  params.reference_mass = 0.02;
  add_water_forces(ps, nb, params, L);
  Vec<3> total = Vec<3>::Zero();
  double scale = 0.0;
  for (const auto& f : ps.force) { total += f; scale += f.norm(); }
  BOOST_TEST(total.norm() <= 1e-12 * scale);
}

BOOST_AUTO_TEST_CASE(momentum_balance_eq_2_3_free_fall) {
  // [thesis eq. 2], [thesis eq. 3]: a lone particle has a = F/m = g exactly.
  ParticleSet<2> ps;
  const std::size_t i = ps.append();
  ps.m[i] = 0.1;
  ps.h[i] = 0.03;
  ps.rho0[i] = ps.rho[i] = 1000.0;
  SimulationParams params;
  params.gravity = {0.0, -9.81};
  params.domain_min = {-10.0, -10.0};
  params.domain_max = {10.0, 10.0};
  Simulator<2> sim(ps, params);
  const double dt = sim.step();
  BOOST_TEST(dt == 0.001);
  BOOST_TEST(sim.particles().v[0][1] == -9.81 * dt, boost::test_tools::tolerance(1e-14));
  BOOST_TEST(acceleration<2>(Vec<2>(0.0, -0.981), 0.1)[1] == -9.81, boost::test_tools::tolerance(1e-14));
}

BOOST_AUTO_TEST_SUITE_END()
