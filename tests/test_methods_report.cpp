// Methods side by side (`sandcastle validate --method`): a tiny resting tank run by SPH and FLIP
// through the validation runner. Each run is an entry with its method and run id; the comparison
// holds each method's value of every metric (the entries' own values, not copies of one run); the
// overlay plots hold each method's simulated series once; baselines are kept per case and method.
#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <fstream>

#include "baseline.hpp"
#include "case/case_file.hpp"
#include "core/errors.hpp"
#include "io/json_reader.hpp"
#include "runner.hpp"
#include "support/process.hpp"

using namespace sc;
namespace fs = std::filesystem;

namespace {

/// A 2-D tank of water 0.06 m wide and 0.1 m deep at spacing 0.01, for 0.05 s.
json tiny_tank() {
  return json::parse(R"({
    "name": "tank",
    "dimension": 2,
    "domain": {"min": [-0.05, -0.05], "max": [0.11, 0.21]},
    "gravity": [0.0, -9.81],
    "time": {"end": 0.05, "dt": 0.001},
    "support_ratio": 2.0,
    "water": {"rest_density": 1000.0, "sound_speed": 20.0, "viscosity": 1.0},
    "blocks": [{"phase": "water", "min": [0.0, 0.0], "max": [0.06, 0.1]}],
    "tank": {"min": [0.0, 0.0], "max": [0.06, 0.16], "sides": {"x-": "no_slip", "x+": "no_slip", "y-": "no_slip", "y+": "open"}},
    "methods": {"flip": {"cell_size": 2.0, "flip_ratio": 0.95, "cfl": 1.0}},
    "validation": {"observer": "hydrostatic", "average_time": 0.02,
                   "metrics": {"pressure_l2": {"max": 10.0}, "surface_drift": {"max": 10.0}, "spurious_speed": {"max": 10.0}}},
    "tiers": {"quick": {"spacings": [0.01]}, "full": {"spacings": [0.01]}}
  })");
}

struct Folder {
  fs::path root;
  explicit Folder(const std::string& name) : root(test::fresh_path(name)) {
    fs::create_directories(root / "cases" / "tank");
    std::ofstream(root / "cases" / "tank" / "case.json") << tiny_tank().dump(1);
  }
  ValidateOptions options(const std::string& run, std::vector<std::string> methods) const {
    ValidateOptions o;
    o.cases_dir = (root / "cases").string();
    o.baselines_dir = (root / "baselines").string();
    o.out_dir = (root / run).string();
    o.plots = false;
    o.methods = std::move(methods);
    return o;
  }
};

const json& entry_of(const json& report, const std::string& id) {
  for (const json& c : report.at("cases"))
    if (c.at("run_id") == id) return c;
  throw std::runtime_error("no entry " + id);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(methods_report)

BOOST_AUTO_TEST_CASE(methods_asked_are_those_the_case_supports_in_order) {
  const CaseSpec spec = load_case(tiny_tank(), "tank.json");
  ValidateOptions o;
  BOOST_TEST(methods_to_run(spec, o) == std::vector<std::string>({"sph"}));
  o.methods = {"all"};
  BOOST_TEST(methods_to_run(spec, o) == std::vector<std::string>({"sph", "flip"}));
  o.methods = {"flip", "dem", "sph"};
  BOOST_TEST(methods_to_run(spec, o) == std::vector<std::string>({"flip", "sph"}));
  BOOST_TEST(run_id(spec, "sph") == "tank");
  BOOST_TEST(run_id(spec, "flip") == "tank.flip");
}

BOOST_AUTO_TEST_CASE(a_tier_that_lists_methods_runs_those_with_all) {
  json doc = tiny_tank();
  doc["tiers"]["quick"]["methods"] = {"sph"};
  const CaseSpec spec = load_case(doc, "tank.json");
  ValidateOptions o;
  o.methods = {"all"};
  o.tier = "quick";
  BOOST_TEST(methods_to_run(spec, o) == std::vector<std::string>({"sph"}));
  o.tier = "full";
  BOOST_TEST(methods_to_run(spec, o) == std::vector<std::string>({"sph", "flip"}));
  o.methods = {"flip"};  // a method asked by name runs in any tier
  o.tier = "quick";
  BOOST_TEST(methods_to_run(spec, o) == std::vector<std::string>({"flip"}));
  BOOST_TEST(spec.parameters_hash == load_case(tiny_tank(), "tank.json").parameters_hash);
}

BOOST_AUTO_TEST_CASE(a_tier_lists_only_methods_the_case_supports_once) {
  for (const json& list : {json{"sph", "dem"}, json{"flip", "flip"}, json::array(), json{3}}) {
    json doc = tiny_tank();
    doc["tiers"]["quick"]["methods"] = list;
    try {
      load_case(doc, "tank.json");
      BOOST_FAIL("accepted tier methods " + list.dump());
    } catch (const InputError& e) {
      BOOST_TEST(std::string(e.what()).find("/tiers/quick/methods") != std::string::npos, e.what());
    }
  }
}

BOOST_AUTO_TEST_CASE(one_case_by_two_methods_side_by_side_with_baselines_per_method) {
  const Folder f("methods_report");
  validate(f.options("run0", {"sph", "flip"}));
  const json report = read_json_file((f.root / "run0" / "report.json").string());
  const json& sph = entry_of(report, "tank");
  const json& flip = entry_of(report, "tank.flip");
  BOOST_TEST(sph.at("name") == "tank");
  BOOST_TEST(flip.at("name") == "tank");
  BOOST_TEST(sph.at("method") == "sph");
  BOOST_TEST(flip.at("method") == "flip");
  BOOST_TEST(sph.at("state_checksum") != flip.at("state_checksum"));  // two different solvers ran
  BOOST_TEST(fs::exists(f.root / "run0" / "tank.flip" / "series.json"));

  BOOST_REQUIRE(report.at("methods").size() == 1u);
  const json& cmp = report.at("methods").at(0);
  BOOST_TEST(cmp.at("methods") == json::array({"sph", "flip"}));
  for (const auto& [name, item] : cmp.at("metrics").items()) {
    BOOST_TEST(item.at("values").at("sph") == sph.at("metrics").at(name).at("value"));
    BOOST_TEST(item.at("values").at("flip") == flip.at("metrics").at(name).at("value"));
  }
  const json overlay = read_json_file((f.root / "run0" / cmp.at("series").get<std::string>()).string());
  int sph_series = 0, flip_series = 0;
  for (const json& s : overlay.at("series")) {
    const std::string n = s.at("name");
    sph_series += n.ends_with("@sph");
    flip_series += n.ends_with("@flip");
  }
  BOOST_TEST(sph_series > 0);
  BOOST_TEST(flip_series == sph_series);

  // Baselines: the case's own method by default, another one only when asked, each in its own file.
  const std::string run0 = (f.root / "run0").string(), baselines = (f.root / "baselines").string();
  BOOST_TEST(write_baselines(run0, baselines, {}) == kSuccess);
  BOOST_TEST(fs::exists(f.root / "baselines" / "tank.json"));
  BOOST_TEST(!fs::exists(f.root / "baselines" / "tank.flip.json"));
  BOOST_TEST(write_baselines(run0, baselines, {"tank"}, {"flip"}) == kSuccess);
  const json blessed = read_json_file(baselines + "/tank.flip.json");
  BOOST_TEST(blessed.at("state_checksum") == flip.at("state_checksum"));

  validate(f.options("run1", {"flip", "sph"}));
  const json again = read_json_file((f.root / "run1" / "report.json").string());
  BOOST_TEST(entry_of(again, "tank.flip").at("baseline").at("status") == "identical");
  BOOST_TEST(entry_of(again, "tank").at("baseline").at("status") == "identical");
  BOOST_TEST(again.at("methods").at(0).at("methods") == json::array({"flip", "sph"}));
}

BOOST_AUTO_TEST_CASE(scene_observer_follows_the_particles_of_a_method_without_ids) {
  // FLIP keeps its particles in one order and gives no ids: the scene observer follows them by index.
  json c = tiny_tank();
  c["sand"] = {{"rest_density", 2650.0}, {"friction_angle", 30.0}};
  c["blocks"] = json::parse(R"([{"phase": "sand", "min": [0.0, 0.0], "max": [0.04, 0.04]}])");
  c["validation"] = {{"observer", "scene"}, {"metrics", {{"escaped", {{"max", 0}}}}}};
  const Folder f("methods_scene");
  std::ofstream(f.root / "cases" / "tank" / "case.json") << c.dump(1);
  BOOST_TEST(validate(f.options("run", {"flip"})) == kSuccess);
  const json report = read_json_file((f.root / "run" / "report.json").string());
  BOOST_TEST(entry_of(report, "tank.flip").at("metrics").at("sand_displaced_fraction_dry").at("value").get<double>() < 1.0);
}

BOOST_AUTO_TEST_CASE(a_named_case_that_supports_none_of_the_methods_is_bad_input) {
  const Folder f("methods_none");
  ValidateOptions o = f.options("run", {"dem"});
  o.cases = {"tank"};
  BOOST_TEST(validate(o) == kBadInput);
}

BOOST_AUTO_TEST_SUITE_END()
