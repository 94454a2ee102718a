// The "meshes" list of a case file: a mesh fills the scene with particles, and each fault is an
// InputError naming the case file and the mesh's JSON path.
#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <fstream>

#include "case/case_file.hpp"
#include "scene/scene_builder.hpp"
#include "support/process.hpp"

using namespace sc;
namespace fs = std::filesystem;

namespace {

const fs::path folder = test::fresh_path("mesh_case");  // one per process: concurrent runs do not share it

/// A 1 x 2 x 1 box (file units), y up, as OBJ in the test folder.
void write_box_obj() {
  fs::create_directories(folder);
  std::ofstream out(folder / "box.obj");
  for (int k = 0; k < 8; ++k) out << "v " << (k & 1) << " " << 2 * ((k >> 1) & 1) << " " << ((k >> 2) & 1) << "\n";
  out << "f 1 3 2\nf 2 3 4\nf 5 6 7\nf 6 8 7\nf 1 2 5\nf 2 6 5\nf 3 7 4\nf 4 7 8\nf 1 5 3\nf 3 5 7\nf 2 4 6\nf 4 8 6\n";
}

json box_case() {
  return json::parse(R"({
    "name": "m", "dimension": 3,
    "domain": {"min": [-1, -1, -1], "max": [2, 2, 2]},
    "gravity": [0, 0, -9.81],
    "time": {"end": 0.1},
    "water": {"rest_density": 1000, "sound_speed": 10},
    "blocks": [],
    "meshes": [{"file": "box.obj", "phase": "water", "up_axis": "y", "size": 0.4, "min_corner": [0.1, 0.1, 0.1]}],
    "tiers": {"quick": {"spacings": [0.05]}, "full": {"spacings": [0.05]}}
  })");
}

std::string write_case(const json& j) {
  write_box_obj();
  std::ofstream(folder / "case.json") << j.dump();
  return (folder / "case.json").string();
}

/// Loads `j` and builds its particles; returns the JSON path of the InputError, or "no error".
std::string error_path(const json& j) {
  try {
    build_scene<3>(load_case(write_case(j)), 0.05);
  } catch (const InputError& e) {
    BOOST_TEST(e.file().find("case.json") != std::string::npos);
    return e.json_path();
  }
  return "no error";
}

}  // namespace

BOOST_AUTO_TEST_SUITE(mesh_case)

BOOST_AUTO_TEST_CASE(mesh_fills_its_placed_box) {
  const CaseSpec c = load_case(write_case(box_case()));
  BOOST_TEST(c.meshes.size() == 1u);
  const ParticleSet<3> ps = build_scene<3>(c, 0.05);
  // size 0.4 scales the 2-unit height to 0.4 m: a 0.2 x 0.2 x 0.4 m box (y up becomes z up).
  BOOST_TEST(ps.size() == 4u * 4u * 8u);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    BOOST_TEST_REQUIRE((ps.phase_of(i) == Phase::Water));
    BOOST_TEST_REQUIRE(ps.x[i].z() > 0.1);
    BOOST_TEST_REQUIRE(ps.x[i].z() < 0.5);
    BOOST_TEST_REQUIRE(ps.x[i].x() < 0.3);
  }
}

BOOST_AUTO_TEST_CASE(a_sand_mesh_fills_with_the_sands_mass_and_rest_density) {
  // Sand from a mesh is sand as from a block: the sand's lattice mass and its rest density, so each
  // particle's rest volume m/ρ0 is the water's (one lattice), and the summed mass is ρ_sand times the
  // sampled volume.
  json j = box_case();
  j["sand"] = {{"rest_density", 2000.0}, {"friction_angle", 35.0}};
  j["meshes"][0]["phase"] = "sand";
  j["blocks"] = json::array({{{"phase", "water"}, {"min", {1.0, 1.0, 1.0}}, {"max", {1.2, 1.2, 1.2}}}});
  const ParticleSet<3> ps = build_scene<3>(load_case(write_case(j)), 0.05);
  std::size_t sand = 0, water = 0;
  double sand_volume = 0.0, water_volume = 0.0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const bool is_sand = ps.phase_of(i) == Phase::Sand;
    BOOST_TEST_REQUIRE(ps.rho0[i] == (is_sand ? 2000.0 : 1000.0));
    (is_sand ? sand_volume : water_volume) = ps.m[i] / ps.rho0[i];
    ++(is_sand ? sand : water);
  }
  BOOST_TEST(sand == 4u * 4u * 8u);
  BOOST_TEST(water > 0u);
  BOOST_TEST(sand_volume == water_volume, boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(each_mesh_fault_names_its_json_path) {
  json missing = box_case(), both = box_case(), outside = box_case(), sand = box_case(), flat = box_case();
  missing["meshes"][0]["file"] = "no_such.obj";
  both["meshes"][0]["scale"] = 2.0;
  outside["meshes"][0]["min_corner"] = json::array({1.9, 0.0, 0.0});
  sand["meshes"][0]["phase"] = "sand";  // the case has no "sand" section
  flat["dimension"] = 2;
  flat["domain"] = json::parse(R"({"min": [-1, -1], "max": [2, 2]})");
  flat["gravity"] = json::array({0.0, -9.81});
  BOOST_TEST(error_path(box_case()) == "no error");
  BOOST_TEST(error_path(missing) == "/meshes/0/file");
  BOOST_TEST(error_path(both) == "/meshes/0/scale");
  BOOST_TEST(error_path(outside) == "/meshes/0");
  BOOST_TEST(error_path(sand) == "/meshes/0/phase");
  BOOST_TEST(error_path(flat) == "/meshes");
}

// A mesh may not reach into a closed tank wall: the wall particles and the mesh's would overlap.
// A tank closed on every side but its top (z+ open): a mesh inside it loads, one sunk into its
// floor or pushed through its x+ wall is refused at its JSON path, and one standing out of the
// open top (inside the domain) loads.
BOOST_AUTO_TEST_CASE(a_mesh_may_cross_an_open_tank_side_but_not_a_closed_one) {
  json inside = box_case();
  inside["tank"] = json::parse(R"({"min": [0, 0, 0], "max": [1, 1, 0.6],
    "sides": {"x-": "no_slip", "x+": "slip", "y-": "slip", "y+": "slip", "z-": "no_slip", "z+": "open"}})");
  json sunk = inside, through = inside, above = inside;
  sunk["meshes"][0]["min_corner"] = json::array({0.1, 0.1, -0.05});
  through["meshes"][0]["min_corner"] = json::array({0.9, 0.1, 0.1});
  above["meshes"][0]["min_corner"] = json::array({0.1, 0.1, 0.4});  // top at 0.8 m, above the tank's 0.6
  BOOST_TEST(error_path(inside) == "no error");
  BOOST_TEST(error_path(sunk) == "/meshes/0");
  BOOST_TEST(error_path(through) == "/meshes/0");
  BOOST_TEST(error_path(above) == "no error");
}

BOOST_AUTO_TEST_CASE(unreadable_mesh_is_an_input_error_at_its_path) {
  json j = box_case();
  j["meshes"][0]["file"] = "empty.obj";
  fs::create_directories(folder);
  std::ofstream(folder / "empty.obj") << "# no triangles\n";
  BOOST_TEST(error_path(j) == "/meshes/0/file");
}

BOOST_AUTO_TEST_SUITE_END()
