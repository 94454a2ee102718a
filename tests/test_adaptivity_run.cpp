// Adaptivity inside a run: elfs of a particle cloud, the surface cap, conservation of whole
// passes (forced merge and split) and the density blend that keeps densities continuous.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <random>

#include "adaptive/adaptivity.hpp"
#include "adaptive/density_blend.hpp"
#include "sph/density.hpp"
#include "support/lattice.hpp"

using namespace sc;

BOOST_TEST_DONT_PRINT_LOG_VALUE(sc::Decision)

namespace {

constexpr double kDx = 0.01, kRho0 = 1000.0;

/// An adaptivity spec for water at spacing kDx with lattice-mass particles (support 2 dx).
AdaptivitySpec water_spec(double lfs_cap_spacings = INFINITY) {
  AdaptivitySpec spec;
  spec.params.alpha = 2.0;
  spec.params.beta = 4.0;
  spec.params.max_level = 6;  // elfs clamp max(alpha r_6, beta r_5) + 2 cells = 0.246 m: above every value tested
  spec.feature.lfs_max = lfs_cap_spacings;
  const double m = lattice_mass<2>(kRho0, kDx, 2.0 * kDx, kernel::DensityKernel::Spiky);
  derive_adaptivity<2>(spec, kDx, m / kRho0);
  return spec;
}

/// A water slab `rows` particles thick and 60 wide, random small velocities.
ParticleSet<2> slab(int rows) {
  ParticleSet<2> ps;
  const ParticleSet<2> lattice = test::square_lattice(60, kDx, 2.0, kRho0, Phase::Water);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  for (std::size_t i = 0; i < lattice.size(); ++i) {
    if (lattice.x[i][1] > (rows - 0.5) * kDx) continue;
    const std::size_t k = ps.append();
    ps.x[k] = lattice.x[i];
    ps.v[k] = Vec<2>(u(rng), u(rng));
    ps.m[k] = lattice.m[i];
    ps.h[k] = lattice.h[i];
    ps.rho0[k] = ps.rho[k] = kRho0;
    ps.phase[k] = lattice.phase[i];
  }
  return ps;
}

/// elfs of the particle nearest to (x, y).
double elfs_near(const ParticleSet<2>& ps, const std::vector<double>& elfs, double x, double y) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < ps.size(); ++i)
    if ((ps.x[i] - Vec<2>(x, y)).norm() < (ps.x[best] - Vec<2>(x, y)).norm()) best = i;
  return elfs[best];
}

}  // namespace

BOOST_AUTO_TEST_SUITE(adaptivity_run)

// The particles are balls of radius dx, so a slab of n rows (centres 0 .. (n-1) dx) is a region
// of thickness T = (n + 1) dx: lfs = T/2 on its faces, and elfs = T/2 + depth below the surface.
BOOST_AUTO_TEST_CASE(particle_elfs_of_a_slab_is_half_thickness_plus_depth) {
  const int rows = 21;
  const ParticleSet<2> ps = slab(rows);
  const std::vector<double> elfs = particle_elfs<2>(ps, water_spec());
  const double T = (rows + 1) * kDx;
  BOOST_TEST(std::abs(elfs_near(ps, elfs, 0.3, 0.0) - (T / 2 + kDx)) < 0.5 * kDx);      // face row
  BOOST_TEST(std::abs(elfs_near(ps, elfs, 0.3, 0.1) - (T / 2 + 11 * kDx)) < 0.5 * kDx);  // middle row
}

// With the lfs cap the surface sizes stay at the cap and grow with depth: elfs = cap + depth.
BOOST_AUTO_TEST_CASE(surface_lfs_cap_keeps_the_surface_fine) {
  const ParticleSet<2> ps = slab(21);
  const std::vector<double> elfs = particle_elfs<2>(ps, water_spec(2.0));
  BOOST_TEST(std::abs(elfs_near(ps, elfs, 0.3, 0.0) - 3.0 * kDx) < 0.5 * kDx);
  BOOST_TEST(std::abs(elfs_near(ps, elfs, 0.3, 0.1) - 13.0 * kDx) < 0.5 * kDx);
  const double r0 = std::sqrt(water_spec().params.finest_volume);  // level-0 particle size
  BOOST_TEST(decide<2>(elfs_near(ps, elfs, 0.3, 0.0), ps.level[0], water_spec().params) == Decision::Keep);
  BOOST_TEST(elfs_near(ps, elfs, 0.3, 0.1) > 4.0 * r0);  // deep inside: a merge candidate
}

// Forced cycles: a merge pass and then split passes back to level 0 keep mass, momentum and the
// centre of mass to round-off, and the split passes restore the particle count.
BOOST_AUTO_TEST_CASE(forced_passes_conserve_and_return_to_the_finest_level) {
  ParticleSet<2> ps = slab(10);
  const std::size_t n0 = ps.size();
  AdaptivitySpec spec = water_spec();
  spec.forced = ForcedCycle{0.2, 1.0};
  AdaptAccount account;
  NeighbourGrid<2> nb;
  for (double t : {0.0, 0.05, 0.15, 0.15, 1.0}) {  // merge, merge, split, split, split
    nb.rebuild(ps);
    adapt_particles<2>(ps, nb, spec, t, account);
  }
  BOOST_TEST(account.merges > n0 / 2);
  BOOST_TEST(account.splits == account.merges);
  BOOST_TEST(ps.size() == n0);
  BOOST_TEST(account.max_mass_rel_error < 1e-14);
  BOOST_TEST(account.max_momentum_error < 1e-14);
  BOOST_TEST(account.max_moment_error < 1e-14);
  BOOST_TEST(account.energy_removed > 0.0);  // the random velocities differ within every pair
}

// After a pass, summation + offset equals every particle's density before the pass (carried
// through the merge as an intensive field), although the summation itself jumps.
BOOST_AUTO_TEST_CASE(density_offsets_make_density_continuous_across_a_pass) {
  ParticleSet<2> ps = slab(20);
  NeighbourGrid<2> nb;
  nb.rebuild(ps);
  compute_density(ps, nb, kernel::DensityKernel::Spiky, 1000.0);
  AdaptivitySpec spec = water_spec();
  spec.forced = ForcedCycle{0.2, 1.0};
  AdaptAccount account;
  adapt_particles<2>(ps, nb, spec, 0.0, account);  // merge: the carried ρ is the pair's mass-weighted ρ
  const std::vector<double> carried = ps.rho;
  nb.rebuild(ps);
  set_density_offsets(ps, nb, kernel::DensityKernel::Spiky, 1000.0);
  compute_density(ps, nb, kernel::DensityKernel::Spiky, 1000.0);
  double largest_jump = 0.0;
  for (std::size_t i = 0; i < ps.size(); ++i) largest_jump = std::max(largest_jump, std::abs(ps.rho[i] - carried[i]));
  BOOST_TEST(largest_jump > 10.0);  // summation alone jumps by > 1 % somewhere
  add_density_offsets(ps);
  for (std::size_t i = 0; i < ps.size(); ++i) BOOST_TEST(ps.rho[i] == carried[i], boost::test_tools::tolerance(1e-12));
  const std::vector<double> offsets = ps.density_offset;
  decay_density_offsets(ps, 0.005, 0.005);  // one blend time: offsets shrink by e
  for (std::size_t i = 0; i < ps.size(); ++i)
    BOOST_TEST(ps.density_offset[i] == offsets[i] / std::exp(1.0), boost::test_tools::tolerance(1e-12));
}

// Only the phases a case names split and merge ("phases" of "adaptive"): a water slab and a sand
// slab beside it, one forced merge pass. With water named, the water merges and with sand named,
// the sand; a phase not named keeps every particle.
BOOST_AUTO_TEST_CASE(only_the_phases_named_split_and_merge) {
  for (const auto& [water, sand] : {std::pair{true, false}, std::pair{false, true}, std::pair{true, true}}) {
    ParticleSet<2> ps = slab(10);
    const std::size_t n = ps.size();
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t k = ps.append();
      ps.x[k] = ps.x[i] + Vec<2>(0.8, 0.0);
      ps.m[k] = 2.65 * ps.m[i];
      ps.h[k] = ps.h[i];
      ps.rho0[k] = ps.rho[k] = 2.65 * kRho0;
      ps.phase[k] = static_cast<std::uint8_t>(Phase::Sand);
    }
    AdaptivitySpec spec = water_spec();
    spec.adapt_water = water;
    spec.adapt_sand = sand;
    spec.forced = ForcedCycle{0.2, 1.0};
    NeighbourGrid<2> nb;
    nb.rebuild(ps);
    AdaptAccount account;
    adapt_particles<2>(ps, nb, spec, 0.0, account);
    std::size_t waters = 0, sands = 0;
    for (std::size_t i = 0; i < ps.size(); ++i) (ps.phase_of(i) == Phase::Water ? waters : sands) += 1;
    BOOST_TEST_MESSAGE("water " << water << ", sand " << sand << ": " << waters << " and " << sands << " of " << n);
    BOOST_TEST((waters < n) == water);
    BOOST_TEST((sands < n) == sand);
  }
}

BOOST_AUTO_TEST_SUITE_END()
