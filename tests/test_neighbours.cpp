// Grid neighbour search against brute force, with unequal support radii.
#include <boost/test/unit_test.hpp>
#include <random>

#include "neighbours/neighbour_grid.hpp"

using namespace sc;

namespace {

template <int D>
void check_against_brute_force(unsigned seed, std::size_t n) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pos(0.0, 1.0), radius(0.03, 0.12);
  ParticleSet<D> ps;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = ps.append();
    for (int d = 0; d < D; ++d) ps.x[i][d] = pos(rng);
    ps.h[i] = radius(rng);
  }
  NeighbourGrid<D> grid;
  grid.rebuild(ps);
  const auto brute = brute_force_neighbours(ps);
  std::size_t pairs = 0;
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<std::uint32_t> got(grid.of(i).begin(), grid.of(i).end());
    std::sort(got.begin(), got.end());
    BOOST_TEST(got == brute[i], boost::test_tools::per_element());
    pairs += got.size();
  }
  BOOST_TEST(pairs > 2 * n);  // the test set really has neighbours
}

}  // namespace

BOOST_AUTO_TEST_SUITE(neighbours)

BOOST_AUTO_TEST_CASE(grid_equals_brute_force_2d) { check_against_brute_force<2>(1, 1500); }
BOOST_AUTO_TEST_CASE(grid_equals_brute_force_3d) { check_against_brute_force<3>(2, 2000); }

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
