// Sweeps over MPI ranks (validation/sweep.hpp): `mpirun -n N sandcastle validate` reports what one
// process reports, whatever N, including the cases that fail; the in-process sweep runs every task
// once and returns the results in task order.
#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <fstream>

#include "io/json_reader.hpp"
#include "support/process.hpp"
#include "sweep.hpp"

using namespace sc;
namespace fs = std::filesystem;

namespace {

const std::string reliability = std::string(SANDCASTLE_SOURCE_DIR) + "/tests/reliability";

/// A folder of four cases: two small dam breaks (different blocks), one that blows up (exit 3) and
/// one whose case file breaks a rule (exit 2). Returns its path.
std::string sweep_cases() {
  const fs::path dir = test::fresh_path("sweep_cases");
  const auto put = [&](const std::string& name, const std::string& text) {
    fs::create_directories(dir / name);
    std::ofstream(dir / name / "case.json") << text;
  };
  json small = read_json_file(reliability + "/small_dam_break.json");
  put("a_small", small.dump());
  small["name"] = "small_wide";
  small["blocks"][0]["max"][0] = 0.15;
  put("b_small_wide", small.dump());
  put("c_unstable", test::read_text(reliability + "/unstable_step.json"));
  put("d_bad", R"({"name": "bad", "dimension": 5})");
  return dir.string();
}

/// The report's cases without what may differ between runs: wall-clock times, and the output
/// folder named in messages.
json comparable(json cases, const std::string& out) {
  for (json& c : cases) {
    c.erase("wall_seconds");
    if (c.contains("resolutions"))
      for (json& r : c["resolutions"]) r.erase("wall_seconds");
    if (c.contains("message")) {
      std::string m = c["message"];
      for (std::size_t k; (k = m.find(out)) != std::string::npos;) m.replace(k, out.size(), "OUT");
      c["message"] = m;
    }
  }
  return cases;
}

const char* mpirun = "/usr/bin/mpirun";

}  // namespace

BOOST_AUTO_TEST_SUITE(sweep)

// One process: each task once, results in task order, the report so far after every task.
BOOST_AUTO_TEST_CASE(in_process_sweep_runs_each_task_once_in_order) {
  std::vector<int> runs(5, 0);
  std::size_t reports = 0;
  const std::vector<std::string> out = sc::sweep(
      {1.0, 5.0, 2.0, 5.0, 0.0}, [&](std::size_t i) { return ++runs[i], "task " + std::to_string(i); },
      [&](const std::vector<std::string>& known) { reports += known.size() == 5; });
  BOOST_TEST(out == std::vector<std::string>({"task 0", "task 1", "task 2", "task 3", "task 4"}),
             boost::test_tools::per_element());
  BOOST_TEST(runs == std::vector<int>(5, 1), boost::test_tools::per_element());
  BOOST_TEST(reports == 5u);
}

// `mpirun -n 2` and `-n 3` (oversubscribed on two cores) give the one-process report: the same
// cases in the same order with the same metrics, checksums and statuses, the case that blows up
// and the bad case file reported as errors and the others finished, and the same exit code (3,
// the blow-up).
BOOST_AUTO_TEST_CASE(validate_over_ranks_reports_what_one_process_reports) {
  if (!sweep_has_mpi() || !fs::exists(mpirun)) {
    BOOST_TEST_MESSAGE("skipped: built without MPI or no " << mpirun);
    return;
  }
  const std::string cases = sweep_cases(), root = test::fresh_path("sweep_out");
  const auto validate = [&](int ranks) {
    const std::string out = root + "/n" + std::to_string(ranks);
    std::vector<std::string> args{"validate", "--tier", "quick", "--cases-dir", cases, "--out", out, "--no-plots"};
    test::ProcessResult r;
    if (ranks == 1) {
      r = test::run_sandcastle(args);
    } else {
      args.insert(args.begin(), {"--oversubscribe", "-n", std::to_string(ranks), SANDCASTLE_BINARY});
      // detect_leaks=0: OpenMPI keeps allocations until exit, which LeakSanitizer (tools/sanitize.sh)
      // would report as the ranks' leaks; the one-process run keeps the leak check.
      test::Child child(args,
                        {"OMP_NUM_THREADS=1", "OMPI_ALLOW_RUN_AS_ROOT=1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1",
                         "ASAN_OPTIONS=detect_leaks=0"},
                        mpirun);
      r = child.wait(240.0);
    }
    BOOST_TEST_INFO(ranks << " ranks: " << r.err);
    BOOST_TEST(!r.timed_out);
    BOOST_TEST(r.exit_code == 3);
    return comparable(read_json_file(out + "/report.json").at("cases"), out);
  };
  const json one = validate(1);
  BOOST_TEST_REQUIRE(one.size() == 4u);
  BOOST_TEST(one[0]["status"] == "pass");
  BOOST_TEST(one[1]["status"] == "pass");
  BOOST_TEST(one[2]["status"] == "error");
  BOOST_TEST(one[3]["status"] == "error");
  for (const int ranks : {2, 3}) {
    const json many = validate(ranks);
    BOOST_TEST_INFO(ranks << " ranks");
    BOOST_TEST(many == one);
  }
  fs::remove_all(cases);
  fs::remove_all(root);
}

BOOST_AUTO_TEST_SUITE_END()
