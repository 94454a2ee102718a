// Convergence studies (validation/convergence.hpp): the observed order is the least-squares slope
// in log-log, and `validate --convergence` reports at each spacing the error the same run reports
// in a tier, alone or over MPI ranks.
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "convergence.hpp"
#include "io/json_reader.hpp"
#include "support/process.hpp"
#include "sweep.hpp"

using namespace sc;
namespace fs = std::filesystem;

BOOST_AUTO_TEST_SUITE(convergence)

// err = 3 dx^1.5 at four spacings gives the order 1.5 to round-off; a point with no error (NaN or
// 0) is left out of the fit; a single usable point gives no order.
BOOST_AUTO_TEST_CASE(observed_order_is_the_log_log_slope) {
  const std::vector<double> dx{0.04, 0.02, 0.01, 0.005};
  std::vector<double> err;
  for (const double h : dx) err.push_back(3.0 * std::pow(h, 1.5));
  BOOST_TEST(observed_order(dx, err) == 1.5, boost::test_tools::tolerance(1e-12));
  err[1] = std::nan("");
  err[2] = 0.0;
  BOOST_TEST(observed_order(dx, err) == 1.5, boost::test_tools::tolerance(1e-12));
  // Noisy errors: the slope of the least-squares line, here through (log dx, log err) with
  // log err = 2 log dx ± 0.1 alternating, which the symmetric noise leaves at 2 ± 0.1-level.
  std::vector<double> noisy;
  for (std::size_t k = 0; k < dx.size(); ++k) noisy.push_back(std::pow(dx[k], 2.0) * std::exp(k % 2 ? 0.1 : -0.1));
  const double x_mean = (std::log(0.04) + std::log(0.02) + std::log(0.01) + std::log(0.005)) / 4.0;
  double sxy = 0.0, sxx = 0.0;
  for (std::size_t k = 0; k < dx.size(); ++k) {
    sxy += (std::log(dx[k]) - x_mean) * std::log(noisy[k]);
    sxx += (std::log(dx[k]) - x_mean) * (std::log(dx[k]) - x_mean);
  }
  BOOST_TEST(observed_order(dx, noisy) == sxy / sxx, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(std::isnan(observed_order({0.02, 0.01}, {0.1, std::nan("")})));
}

// The small dam break with a study at 0.01 and 0.005 m: `validate --convergence` reports for
// pressure_l2 the values the quick tier at the same two spacings reports per resolution (the same
// runs, bitwise), and their log-log slope; over 2 MPI ranks the same.
BOOST_AUTO_TEST_CASE(study_reports_the_tier_errors_and_their_slope) {
  const fs::path dir = test::fresh_path("convergence_cases");
  json c = read_json_file(std::string(SANDCASTLE_SOURCE_DIR) + "/tests/reliability/small_dam_break.json");
  c["tiers"]["quick"]["spacings"] = {0.01, 0.005};
  c["convergence"] = {{"spacings", {0.01, 0.005}}, {"metrics", {{"pressure_l2", 1.0}}}};
  fs::create_directories(dir / "small");
  std::ofstream(dir / "small" / "case.json") << c.dump();
  const std::string out = test::fresh_path("convergence_out");
  const auto validate = [&](const std::string& sub, std::vector<std::string> extra) {
    std::vector<std::string> args{"validate", "--cases-dir", dir.string(), "--out", out + "/" + sub, "--no-plots"};
    args.insert(args.end(), extra.begin(), extra.end());
    const test::ProcessResult r = test::run_sandcastle(args);
    BOOST_TEST_INFO(r.err);
    BOOST_TEST(r.exit_code == 0);
    return read_json_file(out + "/" + sub + "/report.json");
  };
  const json tier = validate("tier", {"--tier", "quick"});
  const json study = validate("study", {"--convergence"});
  BOOST_TEST_REQUIRE(study.at("convergence").size() == 1u);
  const json& m = study["convergence"][0]["metrics"]["pressure_l2"];
  const json& res = tier["cases"][0]["resolutions"];
  BOOST_TEST_REQUIRE(res.size() == 2u);
  std::vector<double> errors;
  for (std::size_t k = 0; k < 2; ++k) {
    errors.push_back(res[k]["metrics"]["pressure_l2"]["value"].get<double>());
    BOOST_TEST(m["errors"][k].get<double>() == errors.back());
  }
  BOOST_TEST(m["observed_order"].get<double>() == std::log(errors[1] / errors[0]) / std::log(0.5),
             boost::test_tools::tolerance(1e-12));
  BOOST_TEST(m["expected_order"].get<double>() == 1.0);
  BOOST_TEST(study["cases"].empty());
  if (sweep_has_mpi() && fs::exists("/usr/bin/mpirun")) {
    test::Child child({"--oversubscribe", "-n", "2", SANDCASTLE_BINARY, "validate", "--cases-dir", dir.string(), "--out",
                       out + "/mpi", "--no-plots", "--convergence"},
                      {"OMP_NUM_THREADS=1", "OMPI_ALLOW_RUN_AS_ROOT=1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1",
                       "ASAN_OPTIONS=detect_leaks=0"},
                      "/usr/bin/mpirun");
    const test::ProcessResult r = child.wait(240.0);
    BOOST_TEST_INFO(r.err);
    BOOST_TEST(r.exit_code == 0);
    const json over = read_json_file(out + "/mpi/report.json");
    BOOST_TEST(over["convergence"][0]["metrics"] == study["convergence"][0]["metrics"]);
  }
  fs::remove_all(dir);
  fs::remove_all(out);
}

BOOST_AUTO_TEST_SUITE_END()
