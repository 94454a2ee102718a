// The layering of docs/architecture.md ("Who may include whom"), checked on the sources: a file of
// solver/ includes only folders of its own layer or below, methods never include one another, and
// no observer includes the SPH simulator. A new folder must be given its layer here.
#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>

#include "support/pattern.hpp"

namespace fs = std::filesystem;

namespace {

/// Layer of each solver folder, bottom (0) to top; folders of one layer may include each other
/// only where docs/architecture.md says so (physics topics build on the ones listed before them).
const std::map<std::string, int> kLayer = {
    {"core", 0},  {"io", 1},      {"geometry", 2}, {"neighbours", 3}, {"parallel", 4}, {"sph", 4},       {"water", 5},
    {"porous", 5}, {"sand", 6},   {"adaptive", 6}, {"boundary", 6},   {"case", 7},      {"scene", 8},
    {"method", 9}, {"simulator", 10}, {"flip", 10}, {"dem", 10}, {"mpm", 10}, {"surface", 4}};
const std::set<std::string> kMethods = {"simulator", "flip", "dem", "mpm"};
/// The one method that includes another (docs/architecture.md): DEM steps the SPH water its grains
/// are coupled to.
const std::set<std::pair<std::string, std::string>> kCoupled = {{"dem", "simulator"}};

/// The project folders a file includes ("io" for #include "io/json_reader.hpp").
std::vector<std::string> included_folders(const fs::path& file) {
  static const sc::test::Pattern include(R"(^\s*#include\s+"([a-z_]+)/)");
  std::vector<std::string> out;
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);)
    if (const auto groups = include.first_in(line)) out.push_back(groups->at(0));
  return out;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(layers)

BOOST_AUTO_TEST_CASE(solver_includes_point_down) {
  const fs::path solver = fs::path(SANDCASTLE_SOURCE_DIR) / "solver";
  for (const auto& entry : fs::recursive_directory_iterator(solver)) {
    if (!entry.is_regular_file()) continue;
    const std::string folder = entry.path().parent_path().filename().string();
    BOOST_TEST_CONTEXT(entry.path().string()) {
      BOOST_TEST_REQUIRE(kLayer.count(folder) == 1u, "folder " << folder << " has no layer in tests/test_layers.cpp");
      const bool registry = entry.path().filename() == "registry.cpp";  // knows every method's adapter
      for (const std::string& dep : included_folders(entry.path())) {
        if (!kLayer.count(dep) || dep == folder) continue;
        if (!registry) BOOST_TEST(kLayer.at(dep) <= kLayer.at(folder), "includes " << dep << "/ from a layer above");
        if (kMethods.count(folder) && kMethods.count(dep) && !kCoupled.count({folder, dep}))
          BOOST_TEST(false, "method " << folder << " includes another method's folder " << dep << "/");
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(observers_see_runs_only_through_the_method_seam) {
  const fs::path validation = fs::path(SANDCASTLE_SOURCE_DIR) / "validation";
  for (const auto& entry : fs::recursive_directory_iterator(validation)) {
    if (!entry.is_regular_file()) continue;
    const bool observer = entry.path().parent_path().filename() == "observers" || entry.path().filename() == "observer.hpp";
    if (!observer) continue;
    std::ifstream in(entry.path());
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    BOOST_TEST(text.find("simulator/simulator.hpp") == std::string::npos, entry.path().string());
  }
}

BOOST_AUTO_TEST_SUITE_END()
