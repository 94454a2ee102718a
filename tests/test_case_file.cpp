// The case loader: a valid case loads; each malformed variant is rejected with an InputError that
// names the file and the JSON path of the offending value.
#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <fstream>

#include "case/case_file.hpp"
#include "neighbours/neighbour_grid.hpp"
#include "scene/scene_builder.hpp"
#include "simulator/simulator.hpp"
#include "sph/density.hpp"
#include "support/process.hpp"

using namespace sc;

namespace {

json valid_case() {
  return json::parse(R"({
    "name": "t", "dimension": 2,
    "domain": {"min": [-1, -1], "max": [1, 1]},
    "gravity": [0, -9.81],
    "time": {"end": 0.1, "dt": 0.001},
    "water": {"rest_density": 1000, "sound_speed": 10},
    "blocks": [{"phase": "water", "min": [0, 0], "max": [0.1, 0.1]}],
    "tank": {"min": [0, 0], "max": [0.5, 0.5], "sides": {"x-": "slip", "x+": "slip", "y-": "no_slip", "y+": "open"}},
    "tiers": {"quick": {"spacings": [0.01]}, "full": {"spacings": [0.01, 0.005]}}
  })");
}

std::string write_temp(const json& j) {
  static const std::string path = test::fresh_path("case_test", ".json");  // one per process
  std::ofstream(path) << j.dump();
  return path;
}

/// Loads `j` and returns the JSON path of the error (or "no error").
std::string error_path(const json& j) {
  try {
    load_case(write_temp(j));
  } catch (const InputError& e) {
    BOOST_TEST(e.file().find("case_test") != std::string::npos);
    BOOST_TEST(!e.rule().empty());
    return e.json_path();
  }
  return "no error";
}

}  // namespace

BOOST_AUTO_TEST_SUITE(case_file)

BOOST_AUTO_TEST_CASE(valid_case_loads) {
  const CaseSpec c = load_case(write_temp(valid_case()));
  BOOST_TEST(c.dimension == 2);
  BOOST_TEST(c.tiers.at("full").spacings.size() == 2u);
  BOOST_TEST((c.tank->rule(1, -1) == WallRule::NoSlip));
  BOOST_TEST((c.tank->rule(1, 1) == WallRule::Open));
  BOOST_TEST((c.tank->rule(0, 1) == WallRule::Slip));
  BOOST_TEST(c.water.rest_density == 1000.0);
}

BOOST_AUTO_TEST_CASE(each_fault_names_its_json_path) {
  struct Fault { std::string pointer; json value; std::string expected_path; };
  const std::vector<Fault> faults = {
      {"/water/rest_density", -1000.0, "/water/rest_density"},       // negative density
      {"/water/rest_density", "1000", "/water/rest_density"},        // wrong type
      {"/time/dt", 0.0, "/time/dt"},                                 // non-positive step
      {"/tiers/quick/spacings/0", -0.01, "/tiers/quick/spacings"},   // negative spacing
      {"/dimension", 4, "/dimension"},                               // out of range
      {"/gravity", json::array({0.0}), "/gravity"},                  // wrong length
      {"/water/viscosity_typo", 0.1, "/water/viscosity_typo"},       // unknown key
      {"/tank/sides/y+", "lid", "/tank/sides/y+"},                   // not one of the choices
      {"/blocks/0/phase", "lava", "/blocks/0/phase"},                // unknown phase
      {"/blocks/0/max", json::array({2.0, 0.1}), "/blocks/0/max"},  // block outside the domain
      {"/blocks/0/angular_velocity", json::array({1.0, 2.0}), "/blocks/0/angular_velocity"},  // 2-D: one number
  };
  for (const Fault& f : faults) {
    json j = valid_case();
    j[json::json_pointer(f.pointer)] = f.value;
    BOOST_TEST(error_path(j) == f.expected_path, "fault at " << f.pointer);
  }
  json missing = valid_case();
  missing["water"].erase("sound_speed");
  BOOST_TEST(error_path(missing) == "/water/sound_speed");
}

BOOST_AUTO_TEST_CASE(missing_file_and_bad_json) {
  BOOST_CHECK_THROW(load_case("/nonexistent/case.json"), InputError);
  const std::string path = test::fresh_path("bad", ".json");
  std::ofstream(path) << "{ \"name\": ";
  BOOST_CHECK_THROW(load_case(path), InputError);
}


// The particle-count guard estimates without building: blocks and tank walls from their lattices,
// so for a case without meshes the estimate must bound the built count from above and stay close
// to it (within 1 %: the lattices are counted as they are built).
BOOST_AUTO_TEST_CASE(particle_estimate_bounds_the_built_scene) {
  const std::string root = SANDCASTLE_SOURCE_DIR;
  for (const char* name : {"hydrostatic", "dam_break_square", "column_collapse", "green_ampt", "wet_sand_collapse"}) {
    const CaseSpec spec = load_case(root + "/cases/" + name + "/case.json");
    const double dx = spec.tiers.at("quick").spacings.back();
    const double built = static_cast<double>(build_scene<2>(spec, dx).size());
    const double estimate = estimate_particles(spec, dx);
    BOOST_TEST_CONTEXT(name << ": built " << built << ", estimated " << estimate) {
      BOOST_TEST(estimate >= built);
      BOOST_TEST(estimate <= 1.01 * built);
    }
  }
}

// blocks[].angular_velocity: the block's particles start in the rigid spin v = ω × (x − x_cm) about
// their centre of mass, so their momentum is zero and their angular momentum is I ω (2-D: I_zz =
// Σ m |x − x_cm|²); the other blocks stay at rest.
BOOST_AUTO_TEST_CASE(spinning_block_starts_in_rigid_rotation_about_its_centre) {
  json j = valid_case();
  j["blocks"].push_back({{"phase", "water"}, {"min", {0.2, 0.0}}, {"max", {0.33, 0.07}}, {"angular_velocity", {3.0}}});
  const CaseSpec spec = load_case(write_temp(j));
  const ParticleSet<2> ps = build_scene<2>(spec, 0.01);
  Vec<2> P = Vec<2>::Zero(), centre = Vec<2>::Zero();
  double M = 0.0, L = 0.0, I = 0.0, rest = 0.0;
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (ps.x[i].x() > 0.15 && ps.phase_of(i) == Phase::Water) {
      M += ps.m[i];
      centre += ps.m[i] * ps.x[i];
    } else {
      rest = std::max(rest, ps.v[i].norm());
    }
  centre /= M;
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (ps.x[i].x() > 0.15 && ps.phase_of(i) == Phase::Water) {
      const Vec<2> r = ps.x[i] - centre;
      P += ps.m[i] * ps.v[i];
      L += ps.m[i] * (r.x() * ps.v[i].y() - r.y() * ps.v[i].x());
      I += ps.m[i] * r.squaredNorm();
    }
  BOOST_TEST(P.norm() < 1e-14 * M);
  BOOST_TEST(std::abs(L / (3.0 * I) - 1.0) < 1e-12);
  BOOST_TEST(rest == 0.0);
}

// The scene of wet_sand_collapse (sand, water above it, porous flow, a tank with no-slip walls on
// x- and y-, a slip wall on x+, open above) at 0.01 m: the summation density [thesis eq. 6] of an
// interior particle of each block is its phase's rest density (each phase's mass is calibrated on
// the lattice with its own rest density); a wall particle is rough exactly when it lies beyond a
// no-slip side; the walls take no part in the porous flow (porosity and held water 0) while the
// sand has the case's porosity.
BOOST_AUTO_TEST_CASE(a_built_scene_gives_each_phase_its_rest_density_and_each_wall_its_side_rule) {
  const CaseSpec spec = load_case(std::string(SANDCASTLE_SOURCE_DIR) + "/cases/wet_sand_collapse/case.json");
  ParticleSet<2> ps = build_scene<2>(spec, 0.01);
  NeighbourGrid<2> nb;
  nb.rebuild(ps);
  compute_density(ps, nb, spec.water.density_kernel, spec.water.rest_density);
  const auto at = [&](double x, double y) {
    for (std::size_t i = 0; i < ps.size(); ++i)
      if ((ps.x[i] - Vec<2>(x, y)).norm() < 1e-9) return i;
    BOOST_FAIL("no particle at (" << x << ", " << y << ")");
    return ps.size();
  };
  const std::size_t sand = at(0.055, 0.105), water = at(0.055, 0.23);  // 2 spacings inside their blocks
  BOOST_TEST((ps.phase_of(sand) == Phase::Sand));
  BOOST_TEST((ps.phase_of(water) == Phase::Water));
  BOOST_TEST(ps.rho[sand] == 2650.0, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(ps.rho[water] == 1000.0, boost::test_tools::tolerance(1e-12));
  std::size_t walls = 0, wrong_rough = 0, porous_walls = 0, sand_porosity = 0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps.phase_of(i) == Phase::Sand && ps.porosity[i] == 0.4) ++sand_porosity;
    if (ps.phase_of(i) != Phase::Boundary) continue;
    ++walls;
    const bool beyond_no_slip = ps.x[i][0] < 0.0 || ps.x[i][1] < 0.0;  // x- and y- are no-slip, x+ slip
    if ((ps.rough[i] != 0) != beyond_no_slip) ++wrong_rough;
    if (ps.porosity[i] != 0.0 || ps.absorbed[i] != 0.0) ++porous_walls;
  }
  BOOST_TEST(walls > 0u);
  BOOST_TEST(wrong_rough == 0u);
  BOOST_TEST(porous_walls == 0u);
  BOOST_TEST(sand_porosity == 10u * 20u);  // every particle of the 0.1 x 0.2 m block
}

// water.artificial_viscosity α: the shear viscosity of Monaghan's artificial viscosity,
// ν = α h c / 8 in 2-D and α h c / 10 in 3-D (Monaghan 2005, Rep. Prog. Phys. 68, §4.2), with h the
// support radius, as the dynamic viscosity μ = ρ0 ν of the viscosity force [thesis eq. 5].
BOOST_AUTO_TEST_CASE(artificial_viscosity_is_monaghans_shear_viscosity) {
  const double alpha = 0.05, c = 10.0, rho0 = 1000.0, dx = 0.01;
  for (const int dimension : {2, 3}) {
    json j = valid_case();
    j["water"] = {{"rest_density", rho0}, {"sound_speed", c}, {"artificial_viscosity", alpha}};
    if (dimension == 3) {
      j["dimension"] = 3;
      j["domain"] = json::parse(R"({"min": [-1, -1, -1], "max": [1, 1, 1]})");
      j["gravity"] = json::array({0.0, 0.0, -9.81});
      j["blocks"][0]["min"] = json::array({0.0, 0.0, 0.0});
      j["blocks"][0]["max"] = json::array({0.1, 0.1, 0.1});
      j.erase("tank");
    }
    const CaseSpec spec = load_case(write_temp(j));
    const double h = spec.support_ratio * dx;
    const double nu = alpha * h * c / (dimension == 2 ? 8.0 : 10.0);
    BOOST_TEST_CONTEXT("dimension " << dimension) {
      BOOST_TEST(SimulationParams::from_case(spec, dx).water.viscosity == rho0 * nu, boost::test_tools::tolerance(1e-12));
    }
  }
}

BOOST_AUTO_TEST_CASE(particle_guard_names_the_case_spacing_and_flag) {
  const CaseSpec spec = load_case(write_temp(valid_case()));
  BOOST_CHECK_NO_THROW(check_particle_count(spec, 0.01, kDefaultMaxParticles, "/tiers/quick/spacings/0"));
  try {
    check_particle_count(spec, 1e-6, kDefaultMaxParticles, "/tiers/quick/spacings/0");
    BOOST_FAIL("a spacing of 1e-6 m must be refused");
  } catch (const InputError& e) {
    BOOST_TEST(e.json_path() == "/tiers/quick/spacings/0");
    BOOST_TEST(e.rule().find("--max-particles") != std::string::npos);
    BOOST_TEST(e.rule().find("1e-06") != std::string::npos);
  }
}
BOOST_AUTO_TEST_SUITE_END()
