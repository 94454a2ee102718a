// The data root (validation/data_root.hpp): cases, baselines, reference data and report scripts are
// found under --root, else SANDCASTLE_ROOT, else the source tree, so an installed or relocated binary
// runs the suite of whatever repository copy it is pointed at.
#include <boost/test/unit_test.hpp>
#include <fstream>

#include "io/json_reader.hpp"
#include "support/process.hpp"

namespace fs = std::filesystem;
using namespace sc;

namespace {

/// A root holding one case, "tiny" (the small reliability dam break, shortened), and nothing else.
std::string make_root() {
  const fs::path root = test::fresh_path("data_root");
  fs::create_directories(root / "cases" / "tiny");
  json c = read_json_file(std::string(SANDCASTLE_SOURCE_DIR) + "/tests/reliability/small_dam_break.json");
  c["name"] = "tiny";
  c["time"]["end"] = 0.1;
  c["validation"]["average_time"] = 0.05;
  c["tiers"]["quick"]["spacings"] = {0.02};
  std::ofstream(root / "cases" / "tiny" / "case.json") << c.dump(1);
  return root.string();
}

/// Checks that the run at `out` validated exactly the root's one case and looked for its baseline
/// under the root (the case's gates are not the point: its metrics may fail, exit code 1).
void check_ran_the_root(const test::ProcessResult& r, const std::string& out, const std::string& root) {
  BOOST_TEST_CONTEXT("stderr: " << r.err) {
    BOOST_TEST((r.exit_code == 0 || r.exit_code == 1));
    const json cases = read_json_file(out + "/report.json").at("cases");
    BOOST_TEST(cases.size() == 1u);
    BOOST_TEST(cases.at(0).at("name").get<std::string>() == "tiny");
    BOOST_TEST(cases.at(0).at("baseline").at("file").get<std::string>() == root + "/reference/baselines/tiny.json");
  }
}

}  // namespace

BOOST_AUTO_TEST_SUITE(data_root)

BOOST_AUTO_TEST_CASE(validate_reads_the_cases_of_the_environment_root) {
  const std::string root = make_root(), out = test::fresh_path("data_root_out");
  const auto r = test::run_sandcastle({"validate", "--no-plots", "--out", out}, 120.0,
                                      {"OMP_NUM_THREADS=1", "SANDCASTLE_ROOT=" + root});
  check_ran_the_root(r, out, root);
  fs::remove_all(root);
  fs::remove_all(out);
}

BOOST_AUTO_TEST_CASE(the_flag_overrides_the_environment) {
  const std::string root = make_root(), out = test::fresh_path("data_root_out");
  const auto r = test::run_sandcastle({"validate", "--no-plots", "--out", out, "--root", root}, 120.0,
                                      {"OMP_NUM_THREADS=1", "SANDCASTLE_ROOT=/nonexistent/sandcastle"});
  check_ran_the_root(r, out, root);
  fs::remove_all(root);
  fs::remove_all(out);
}

BOOST_AUTO_TEST_CASE(a_root_without_cases_is_bad_input_naming_its_origin) {
  const std::string out = test::fresh_path("data_root_out");
  const auto r = test::run_sandcastle({"validate", "--no-plots", "--out", out}, 30.0,
                                      {"OMP_NUM_THREADS=1", "SANDCASTLE_ROOT=/nonexistent/sandcastle"});
  BOOST_TEST(r.exit_code == 2);
  BOOST_TEST(r.err.find("SANDCASTLE_ROOT") != std::string::npos);
  BOOST_TEST(!fs::exists(out));
}

BOOST_AUTO_TEST_SUITE_END()
