// Regression baselines: the series difference (resampling, abscissa choice), the "regression"
// block of a case file, and the end-to-end check of a regression: a copy of a case with its water
// viscosity doubled is reported as changed, with the delta on the front series, while an untouched
// case is identical to its baseline; `sandcastle compare` of the two runs reports the same deltas.
#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <fstream>

#include <omp.h>

#include "baseline.hpp"
#include "compare.hpp"
#include "case/case_file.hpp"
#include "run_record.hpp"
#include "support/process.hpp"

using namespace sc;
namespace fs = std::filesystem;

namespace {

/// A dam break of 6 x 6 particles for 0.1 s: runs in a fraction of a second.
json tiny_case(const std::string& name, double viscosity, const json& regression) {
  json c = json::parse(R"({
    "dimension": 2,
    "domain": {"min": [-0.05, -0.05], "max": [0.45, 0.25]},
    "gravity": [0.0, -9.81],
    "time": {"end": 0.1, "dt": 0.001},
    "water": {"rest_density": 1000.0, "sound_speed": 15.0},
    "blocks": [{"phase": "water", "min": [0.0, 0.0], "max": [0.06, 0.06]}],
    "tank": {"min": [0.0, 0.0], "max": [0.4, 0.2], "sides": {"x-": "slip", "x+": "slip", "y-": "slip", "y+": "open"}},
    "validation": {"observer": "dam_break",
                   "front_reference": "reference/data/martin_moyce_1952_square_front.csv",
                   "height_reference": "reference/data/martin_moyce_1952_square_height.csv"},
    "tiers": {"quick": {"spacings": [0.01]}, "full": {"spacings": [0.01]}}
  })");
  c["name"] = name;
  c["water"]["viscosity"] = viscosity;
  c["regression"] = regression;
  return c;
}

void write_case(const fs::path& cases_dir, const json& c) {
  fs::create_directories(cases_dir / c.at("name").get<std::string>());
  std::ofstream(cases_dir / c.at("name").get<std::string>() / "case.json") << c.dump(1);
}

/// A fresh temporary folder for one test.
fs::path temp_folder(const std::string& name) {
  const fs::path dir = test::fresh_path(name);
  fs::create_directories(dir);
  return dir;
}

ValidateOptions options(const fs::path& root, const std::string& run) {
  ValidateOptions o;
  o.cases_dir = (root / "cases").string();
  o.baselines_dir = (root / "baselines").string();
  o.out_dir = (root / run).string();
  o.plots = false;
  return o;
}

json baseline_of(const fs::path& run_dir, const std::string& name) {
  std::ifstream in(run_dir / "report.json");
  const json report = json::parse(in);
  for (const json& c : report.at("cases"))
    if (c.at("name") == name) return c.at("baseline");
  return nullptr;
}

/// One OpenMP thread while a test runs: the tiny cases gain nothing from two, and runs are bitwise
/// the same at any thread count. Restores the previous count.
struct OneThread {
  int saved = omp_get_max_threads();
  OneThread() { omp_set_num_threads(1); }
  ~OneThread() { omp_set_num_threads(saved); }
};

Series series(std::vector<double> x, std::vector<double> y) { return {"s", "x", "y", std::move(x), std::move(y)}; }

}  // namespace

BOOST_AUTO_TEST_SUITE(baseline)

BOOST_AUTO_TEST_CASE(series_difference_resamples_onto_the_baseline_abscissae) {
  const Series base = series({0.0, 1.0, 2.0}, {0.0, 1.0, 2.0});
  const Series finer = series({0.0, 0.5, 1.0, 1.5, 2.0}, {0.0, 0.5, 1.0, 1.5, 2.0});  // same line, more samples
  BOOST_TEST(series_difference(base, finer).relative_rms == 0.0);
  const Series shifted = series({0.0, 2.0}, {0.5, 2.5});  // y + 0.5
  const SeriesDelta d = series_difference(base, shifted);
  BOOST_TEST(d.max_difference == 0.5, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(d.relative_rms == 0.5 / std::sqrt(5.0 / 3.0), boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(a_profile_is_compared_along_its_increasing_coordinate) {
  // pressure (x, decreasing) against height (y, increasing): compare the pressures
  const Series base = series({3.0, 2.0, 1.0}, {0.0, 1.0, 2.0});
  const Series moved = series({3.0, 2.0, 1.3}, {0.0, 1.0, 2.0});
  BOOST_TEST(series_difference(base, moved).max_difference == 0.3, boost::test_tools::tolerance(1e-12));
  const Series not_monotone = series({1.0, 0.0, 1.0}, {0.0, 1.0, 0.0});
  BOOST_TEST(!series_difference(base, not_monotone).note.empty());
}

BOOST_AUTO_TEST_CASE(a_thinned_time_series_still_compares_identical) {
  Series full = series({}, {});
  for (int k = 0; k <= 5000; ++k) {
    full.x.push_back(1e-4 * k);
    full.y.push_back(std::sin(1e-3 * k));
  }
  const Series thin = thinned(full, 2000);
  BOOST_TEST(thin.x.size() <= 2000u);
  BOOST_TEST(thin.x.back() == full.x.back());
  BOOST_TEST(series_difference(thin, full).max_difference == 0.0);  // bitwise: no false "changed"
  const Series profile = series({1.0, 0.0, 1.0}, {1.0, 0.0, 1.0});  // compared point by point: kept whole
  BOOST_TEST(thinned(profile, 2).x.size() == 3u);
}

BOOST_AUTO_TEST_CASE(metric_difference_handles_null) {
  BOOST_TEST(metric_difference(2.0, 2.5).relative == 0.25);
  BOOST_TEST(metric_difference(NAN, NAN).delta == 0.0);
  BOOST_TEST(std::isinf(metric_difference(1.0, NAN).relative));
}

BOOST_AUTO_TEST_CASE(regression_block_is_checked_on_load) {
  const fs::path dir = temp_folder("regression_block");
  const json limits = {{"series", {{"*", {{"relative", 0.05}}}, {"front_sim", {{"absolute", 0.1}}}}}};
  write_case(dir, tiny_case("c", 0.2, limits));
  const CaseSpec spec = load_case((dir / "c" / "case.json").string());
  BOOST_TEST(*spec.regression.for_series("height_sim").relative == 0.05);
  BOOST_TEST(!spec.regression.for_series("front_sim").relative);
  BOOST_TEST(*spec.regression.for_metric("front_rms").relative == 0.1);  // built-in default
  for (const json& bad : {json{{"series", {{"front_sim", {{"relativ", 0.1}}}}}},
                          json{{"series", {{"front_sim", json::object()}}}},
                          json{{"metrics", {{"front_rms", {{"absolute", -1.0}}}}}}}) {
    write_case(dir, tiny_case("c", 0.2, bad));
    BOOST_CHECK_THROW(load_case((dir / "c" / "case.json").string()), InputError);
  }
}

BOOST_AUTO_TEST_CASE(parameters_hash_ignores_notes_and_follows_physics) {
  const json c = tiny_case("c", 0.2, json::object());
  json noted = c;
  noted["description"] = "changed words";
  noted["water"]["comment"] = "a note";
  BOOST_TEST(parameters_hash(noted) == parameters_hash(c));
  BOOST_TEST(parameters_hash(tiny_case("c", 0.4, json::object())) != parameters_hash(c));
}

BOOST_AUTO_TEST_CASE(doubled_viscosity_is_reported_changed_untouched_case_identical) {
  const OneThread one_thread;
  const fs::path root = temp_folder("baseline_acceptance");
  const json generous = {{"series", {{"*", {{"relative", 0.5}}}}}, {"metrics", {{"*", {{"relative", 1.0}}}}}};
  write_case(root / "cases", tiny_case("untouched", 0.2, generous));
  write_case(root / "cases", tiny_case("viscous", 0.2, generous));
  BOOST_TEST(validate(options(root, "run0")) == kSuccess);
  BOOST_TEST(baseline_of(root / "run0", "viscous").at("status") == "missing");
  BOOST_TEST(write_baselines((root / "run0").string(), (root / "baselines").string(), {}) == kSuccess);

  write_case(root / "cases", tiny_case("viscous", 0.4, generous));
  BOOST_TEST(validate(options(root, "run1")) == kSuccess);  // changed within limits still passes
  BOOST_TEST(baseline_of(root / "run1", "untouched").at("status") == "identical");
  const json b = baseline_of(root / "run1", "viscous");
  BOOST_TEST(b.at("status") == "changed");
  BOOST_TEST(b.at("parameters_changed") == true);
  BOOST_TEST(b.at("series").at("front_sim").at("relative_rms").get<double>() > 1e-4);
  BOOST_TEST(b.at("series").at("front_sim").at("max_difference").get<double>() > 1e-3);
  BOOST_TEST(b.at("series").at("front_martin_moyce").at("max_difference").get<double>() == 0.0);
  BOOST_TEST(b.at("metrics").at("front_rms").at("delta").get<double>() != 0.0);

  const json diff = compare_document((root / "run0").string(), (root / "run1").string());  // sandcastle compare
  BOOST_TEST(diff.at("cases").at(0).at("identical") == true);
  const json& moved = diff.at("cases").at(1);
  BOOST_TEST(moved.at("identical") == false);
  BOOST_TEST(moved.at("metrics").at("front_rms").at("delta") == b.at("metrics").at("front_rms").at("delta"));
  BOOST_TEST(moved.at("series").at("front_sim").at("relative_rms") == b.at("series").at("front_sim").at("relative_rms"));

  json strict = generous;
  strict["series"]["front_sim"] = {{"relative", 1e-6}};
  write_case(root / "cases", tiny_case("viscous", 0.4, strict));
  BOOST_TEST(validate(options(root, "run2")) == kCaseFailed);  // a regression fails validate
  const json r = baseline_of(root / "run2", "viscous");
  BOOST_TEST(r.at("status") == "regressed");
  BOOST_TEST(r.at("failed") == json::array({"front_sim"}));
}

BOOST_AUTO_TEST_CASE(a_limit_on_an_unknown_series_is_bad_input) {
  const OneThread one_thread;
  const fs::path root = temp_folder("baseline_typo");
  write_case(root / "cases", tiny_case("typo", 0.2, {{"series", {{"front_simm", {{"relative", 0.1}}}}}}));
  BOOST_TEST(validate(options(root, "run")) == kBadInput);
}

BOOST_AUTO_TEST_SUITE_END()
