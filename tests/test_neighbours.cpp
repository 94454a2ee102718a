// Grid neighbour search against brute force, with unequal support radii.
#include <boost/test/unit_test.hpp>
#include <algorithm>
#include <omp.h>
#include <random>
#include <set>

#include "neighbours/neighbour_grid.hpp"

using namespace sc;

namespace {

/// Random particles with supports in [h_min, h_max]; with `walls`, every third is a fixed wall
/// particle and half of those porous.
template <int D>
ParticleSet<D> random_particles(unsigned seed, std::size_t n, bool walls, double h_min = 0.03, double h_max = 0.12) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pos(0.0, 1.0), radius(h_min, h_max);
  ParticleSet<D> ps;
  if (walls) ps.add_porous_fields();
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = ps.append();
    for (int d = 0; d < D; ++d) ps.x[i][d] = pos(rng);
    ps.h[i] = radius(rng);
    if (walls && k % 3 == 0) ps.phase[i] = static_cast<std::uint8_t>(Phase::Boundary);
    if (walls && k % 6 == 0) ps.porosity[i] = 0.4;
  }
  return ps;
}

template <int D>
void check_against_brute_force(unsigned seed, std::size_t n, bool walls, double h_min = 0.03, double h_max = 0.12) {
  const ParticleSet<D> ps = random_particles<D>(seed, n, walls, h_min, h_max);
  NeighbourGrid<D> grid;
  grid.rebuild(ps);
  const auto brute = brute_force_neighbours(ps);
  std::size_t pairs = 0, inert_pairs = 0;
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<std::uint32_t> got(grid.of(i).begin(), grid.of(i).end());
    std::sort(got.begin(), got.end());
    BOOST_TEST(got == brute[i], boost::test_tools::per_element());
    pairs += got.size();
    for (const auto j : got) inert_pairs += ps.inert(i) && ps.inert(j);
  }
  BOOST_TEST(pairs > 2 * n);  // the test set really has neighbours
  BOOST_TEST(inert_pairs == 0u);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(neighbours)

BOOST_AUTO_TEST_CASE(grid_equals_brute_force_2d) { check_against_brute_force<2>(1, 1500, false); }
BOOST_AUTO_TEST_CASE(grid_equals_brute_force_3d) { check_against_brute_force<3>(2, 2000, false); }
BOOST_AUTO_TEST_CASE(grid_with_walls_equals_brute_force_2d) { check_against_brute_force<2>(3, 1500, true); }
BOOST_AUTO_TEST_CASE(grid_with_walls_equals_brute_force_3d) { check_against_brute_force<3>(4, 2000, true); }
// Small supports: over 16,384 slots (two cells each), so the slots' prefix sum runs in several parts.
BOOST_AUTO_TEST_CASE(grid_of_many_cells_equals_brute_force_3d) { check_against_brute_force<3>(8, 8000, true, 0.035, 0.045); }

// Binning sorts in one block of particles per thread (with enough particles): the lists, in their
// order, must be those of one thread.
BOOST_AUTO_TEST_CASE(lists_do_not_depend_on_the_threads) {
  const ParticleSet<3> ps = random_particles<3>(5, 20000, true);
  const int threads = omp_get_max_threads();
  NeighbourGrid<3> one, two;
  omp_set_num_threads(1);
  one.rebuild(ps);
  omp_set_num_threads(2);
  two.rebuild(ps);
  omp_set_num_threads(threads);
  BOOST_TEST(one.total_pairs() > 2 * ps.size());
  for (std::size_t i = 0; i < ps.size(); ++i) BOOST_TEST(std::ranges::equal(one.of(i), two.of(i)));
}

BOOST_AUTO_TEST_CASE(sorting_the_particles_only_relabels_the_lists) {
  // Putting the particles in the grid's storage order (ParticleSet::permute) relabels the lists and
  // nothing else; afterwards the non-inert particles come first, each group in cell order.
  ParticleSet<3> ps = random_particles<3>(5, 1500, true);
  NeighbourGrid<3> grid;
  grid.rebuild(ps);
  std::vector<std::set<std::int64_t>> before(ps.size());
  for (std::size_t i = 0; i < ps.size(); ++i)
    for (const auto j : grid.of(i)) before[ps.id[i]].insert(ps.id[j]);
  ps.permute(grid.storage_order());
  grid.rebuild(ps);
  std::size_t inert_before_other = 0;
  for (std::size_t i = 1; i < ps.size(); ++i) inert_before_other += ps.inert(i - 1) && !ps.inert(i);
  BOOST_TEST(inert_before_other == 0u);
  const std::vector<std::size_t>& order = grid.storage_order();
  BOOST_TEST(std::is_sorted(order.begin(), order.end()));  // already in storage order
  for (std::size_t i = 0; i < ps.size(); ++i) {
    std::set<std::int64_t> after;
    for (const auto j : grid.of(i)) after.insert(ps.id[j]);
    BOOST_TEST((after == before[ps.id[i]]));
  }
}

// A step re-bins only the particles that move (bin_moving) and keeps the walls' cells: its lists,
// in their order, must be those of a full bin, after moves inside the grid, after a reorder, after
// a compaction that removed and added moving particles, after one that removed a wall, and after a
// move out of the walls' box that widens the grid.
BOOST_AUTO_TEST_CASE(rebinning_the_moving_particles_only_gives_the_lists_of_a_full_bin) {
  ParticleSet<3> ps = random_particles<3>(6, 3000, true);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> shift(-0.04, 0.04);
  NeighbourGrid<3> kept, full;
  kept.rebuild(ps);
  for (int step = 0; step < 7; ++step) {
    for (std::size_t i = 0; i < ps.size(); ++i)
      if (ps.moves(i))
        for (int d = 0; d < 3; ++d) ps.x[i][d] = std::clamp(ps.x[i][d] + shift(rng), 0.1, 0.9);  // inside the walls
    if (step == 2) ps.permute(kept.storage_order());
    if (step == 3 || step == 5) {  // step 3: water removed and added (walls kept); step 5: a wall removed
      std::size_t i = 0;
      while (step == 3 ? !ps.moves(i) : !ps.inert(i)) ++i;
      ps.queue_remove(i);
      ParticleSet<3>& add = ps.additions();
      const std::size_t k = add.append();
      add.x[k] = Vec<3>(0.5, 0.5, 0.5);
      add.h[k] = 0.1;
      ps.compact();
    }
    if (step == 4) ps.x[std::ranges::find(ps.phase, std::uint8_t(Phase::Water)) - ps.phase.begin()] = Vec<3>(1.3, 0.5, -0.2);
    kept.bin_moving(ps);
    kept.find_pairs(ps);
    full.rebuild(ps);
    BOOST_TEST(kept.total_pairs() == full.total_pairs());
    for (std::size_t i = 0; i < ps.size(); ++i) BOOST_TEST(std::ranges::equal(kept.of(i), full.of(i)));
  }
  BOOST_TEST(full.total_pairs() > 2 * ps.size());
}

BOOST_AUTO_TEST_CASE(pair_rule_uses_the_larger_support) {
  ParticleSet<2> ps;
  ps.append();
  ps.append();
  ps.x[1] = Vec<2>(0.5, 0.0);
  ps.h[0] = 0.6;  // i reaches j, j does not reach i: still a pair, for both
  ps.h[1] = 0.1;
  NeighbourGrid<2> grid;
  grid.rebuild(ps);
  BOOST_TEST(grid.of(0).size() == 2u);
  BOOST_TEST(grid.of(1).size() == 2u);
}

BOOST_AUTO_TEST_SUITE_END()
