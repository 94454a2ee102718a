// The machine probe's kernels (validation/probe.hpp) do the work they are timed for: the triad
// writes b + s c into every element at any thread count, and the multiply-add chains end at the
// closed form of x ← x m + c, so neither can be optimised away or count work it skips.
#include <omp.h>

#include <boost/test/unit_test.hpp>
#include <cmath>
#include <numbers>

#include <filesystem>
#include <fstream>

#include "core/errors.hpp"
#include "probe.hpp"
#include "roofline.hpp"
#include "support/process.hpp"

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

// The roofline of bench (validation/roofline.hpp): a stage's evaluations are the sum of its passes'
// list entries, its floor the larger of bytes over bandwidth and flops over flop rate, and its
// fraction of the limit that floor over the measured time. Limits and times are chosen so that
// one stage is bound by each limit.
BOOST_AUTO_TEST_CASE(roofline_reads_each_stage_against_the_larger_floor) {
  ListEntries e;
  e.water = 3000.0;
  e.sand = 1000.0;
  e.boundary = 500.0;
  const ProbeRow limits{2, 1e9, 1e9};  // 1 GB/s, 1 Gflop/s
  const json ms = {{"neighbours", 100.0}, {"density", 2.0}, {"forces", 50.0}};
  const json r = roofline(3, e, 9000.0, ms, true, limits, "test");
  const json& st = r["stages"];
  BOOST_TEST(st["density"]["pair_evaluations_per_step"].get<double>() == 4500.0);       // moving + wall lists
  BOOST_TEST(st["forces"]["pair_evaluations_per_step"].get<double>() == 3000.0 + 3 * 1000.0 + 4000.0);  // water, 3 sand passes, moment
  BOOST_TEST(st["neighbours"]["pair_evaluations_per_step"].get<double>() == 27.0 / (4.0 / 3.0 * std::numbers::pi) * 4500.0,
             boost::test_tools::tolerance(1e-12));
  for (const auto& [name, s] : st.items()) {
    const double bytes = s["bytes_per_step"].get<double>(), flops = s["flops_per_step"].get<double>();
    const double floor = std::max(bytes / 1e9, flops / 1e9);
    BOOST_TEST(s["floor_ms"].get<double>() == 1e3 * floor, boost::test_tools::tolerance(1e-12));
    BOOST_TEST(s["fraction_of_limit"].get<double>() == floor / (ms[name].get<double>() / 1e3), boost::test_tools::tolerance(1e-12));
    BOOST_TEST(s["bound"].get<std::string>() == (bytes >= flops ? "memory" : "compute"));
    BOOST_TEST(s["bytes_per_particle"].get<double>() == bytes / 9000.0, boost::test_tools::tolerance(1e-12));
    BOOST_TEST(s["pair_evaluations_per_s"].get<double>() ==
                   s["pair_evaluations_per_step"].get<double>() / (ms[name].get<double>() / 1e3),
               boost::test_tools::tolerance(1e-12));
    BOOST_TEST(bytes > flops);  // every pass reads more bytes than it does flops per pair
  }
  // Without the gradient correction the forces lose the moment matrix's pass.
  const json plain = roofline(3, e, 9000.0, ms, false, limits, "test");
  BOOST_TEST(plain["stages"]["forces"]["pair_evaluations_per_step"].get<double>() == 6000.0);
  // A flop rate far below the bandwidth makes every stage compute-bound.
  const json slow = roofline(3, e, 9000.0, ms, true, ProbeRow{2, 1e12, 1e6}, "test");
  for (const auto& [name, s] : slow["stages"].items()) {
    BOOST_TEST(s["bound"].get<std::string>() == "compute");
    BOOST_TEST(s["fraction_of_limit"].get<double>() == s["flops_per_step"].get<double>() / 1e6 / (ms[name].get<double>() / 1e3),
               boost::test_tools::tolerance(1e-12));
  }
}

BOOST_AUTO_TEST_CASE(limits_come_from_the_probe_row_at_the_thread_count) {
  const std::filesystem::path dir = test::fresh_path("limits_test");
  std::filesystem::create_directories(dir);
  const std::string file = (dir / "probe.json").string();
  std::ofstream(file) << R"({"rows": [{"threads": 1, "bandwidth_bytes_per_s": 3e10, "flops_per_s": 1e10},
                                      {"threads": 2, "bandwidth_bytes_per_s": 5e10, "flops_per_s": 2e10}]})";
  const ProbeRow two = bench_limits(file, 2);
  BOOST_TEST(two.bandwidth == 5e10);
  BOOST_TEST(two.flops == 2e10);
  try {
    bench_limits(file, 4);
    BOOST_FAIL("a probe without the thread count's row was accepted");
  } catch (const InputError& err) {
    BOOST_TEST(err.json_path() == "/rows");
  }
  std::ofstream(file) << R"({"rows": [{"threads": 2, "bandwidth_bytes_per_s": -1, "flops_per_s": 2e10}]})";
  try {
    bench_limits(file, 2);
    BOOST_FAIL("a negative bandwidth was accepted");
  } catch (const InputError& err) {
    BOOST_TEST(err.json_path() == "/rows/0/bandwidth_bytes_per_s");
  }
  std::filesystem::remove_all(dir);
}

BOOST_AUTO_TEST_SUITE_END()
