// The machine probe's kernels (validation/probe.hpp) do the work they are timed for: the triad
// writes b + s c into every element at any thread count, and the multiply-add chains end at the
// closed form of x ← x m + c, so neither can be optimised away or count work it skips.
#include <omp.h>

#include <boost/test/unit_test.hpp>
#include <cmath>

#include "probe.hpp"

using namespace sc;

BOOST_AUTO_TEST_SUITE(probe)

BOOST_AUTO_TEST_CASE(triad_writes_b_plus_s_c_everywhere) {
  const std::size_t n = 100003;
  std::vector<double> a(n, -1.0), b(n), c(n);
  for (std::size_t i = 0; i < n; ++i) b[i] = 0.25 * i, c[i] = 3.0 - i;
  for (const int threads : {1, 2}) {
    omp_set_num_threads(threads);
    triad(a, b, c, 0.5);
    std::size_t wrong = 0;
    for (std::size_t i = 0; i < n; ++i) wrong += a[i] != b[i] + 0.5 * c[i];
    BOOST_TEST(wrong == 0u);
  }
}

// x_k = m^k x0 + c (1 − m^k)/(1 − m); 13 chains (not a multiple of the 8 advanced together) sum
// to 13 x_k, within the round-off of k = 10^5 steps.
BOOST_AUTO_TEST_CASE(chains_end_at_the_closed_form) {
  const long k = 100000;
  const double x0 = 2.0, m = 0.99999, c = 1e-5;
  const double mk = std::pow(m, static_cast<double>(k));
  const double exact = mk * x0 + c * (1.0 - mk) / (1.0 - m);
  for (const int threads : {1, 2}) {
    omp_set_num_threads(threads);
    BOOST_TEST(multiply_add_chains(k, 13, x0, m, c) == 13.0 * exact, boost::test_tools::tolerance(1e-9));
  }
}

BOOST_AUTO_TEST_SUITE_END()
