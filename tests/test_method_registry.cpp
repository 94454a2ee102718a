// The method seam (solver/method/): a run built through the registry steps, shows its state
// through the method-neutral ParticleView exactly as its checksum hashes it, is deterministic,
// resumes bitwise from its own checkpoint; an unknown or unsupported method name is bad input
// (exit 2) naming the case file and the JSON path, before anything is allocated.
#include <omp.h>

#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <fstream>

#include "case/case_file.hpp"
#include "method/registry.hpp"
#include "mpm/mpm_method.hpp"
#include "simulator/sph_probe.hpp"
#include "support/process.hpp"

namespace fs = std::filesystem;
using namespace sc;

namespace {

const std::string small_case = std::string(SANDCASTLE_SOURCE_DIR) + "/tests/reliability/small_dam_break.json";
constexpr double kSpacing = 0.02;  // coarser than the case's tiers: a few hundred particles

/// The ParticleSet::checksum of positions and velocities copied out of a view: equal to the
/// method's checksum exactly when the view shows the state the method hashes.
std::string view_checksum(const ParticleView<2>& view) {
  ParticleSet<2> copy;
  for (std::size_t i = 0; i < view.size(); ++i) {
    const std::size_t k = copy.append();
    copy.x[k] = view.x[i];
    copy.v[k] = view.v[i];
  }
  return copy.checksum();
}

/// Writes `doc` to a fresh temporary case file and returns its path.
std::string write_case(const json& doc) {
  const std::string path = test::fresh_path("method_case", ".json");
  std::ofstream(path) << doc.dump();
  return path;
}

json small_case_json() {
  std::ifstream in(small_case);
  return json::parse(in);
}

/// The small dam break with a sand block beside the water, run by FLIP (its "methods"/"flip").
json small_flip_case_json() {
  json doc = small_case_json();
  doc["sand"] = {{"rest_density", 2650.0}, {"friction_angle", 30.0}, {"cohesion", 0.0}};
  doc["blocks"].push_back({{"phase", "sand"}, {"min", {0.2, 0.0}}, {"max", {0.3, 0.1}}});
  doc["methods"] = {{"flip", {{"cell_size", 2.0}, {"flip_ratio", 0.95}}}};
  return doc;
}

/// A sand column 0.1 m x 0.1 m on the floor of the small dam break's tank, run by DEM.
json small_dem_case_json() {
  json doc = small_case_json();
  doc["sand"] = {{"rest_density", 2650.0}, {"friction_angle", 30.0}, {"cohesion", 0.0}};
  doc["blocks"] = json::array({{{"phase", "sand"}, {"min", {0.0, 0.0}}, {"max", {0.1, 0.1}}}});
  doc["methods"] = {{"dem", {{"friction", 0.5}, {"rolling_friction", 0.3}}}};
  return doc;
}

/// The small dam break with a sand block beside the water, run by MPM (its "methods"/"mpm").
json small_mpm_case_json() {
  json doc = small_flip_case_json();
  doc["methods"] = {{"mpm", {{"cell_size", 2.0}, {"cfl", 0.4}}}};
  return doc;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(method_registry)

BOOST_AUTO_TEST_CASE(a_run_built_through_the_registry_steps_and_its_view_matches_its_state) {
  const CaseSpec spec = load_case(small_case);
  BOOST_TEST(spec.method == "sph");
  const std::unique_ptr<Method<2>> run = make_method<2>(spec, kSpacing);
  BOOST_TEST(run->name() == "sph");
  const std::string initial = run->checksum();
  const double water0 = total_water(run->particles());
  BOOST_TEST(water0 > 0.0);
  double elapsed = 0.0;
  for (int k = 0; k < 40; ++k) elapsed += run->step();
  BOOST_TEST(run->steps() == 40);
  BOOST_TEST(run->time() == elapsed);  // the clock is the sum of the steps taken, bitwise
  const ParticleView<2> view = run->particles();
  BOOST_TEST(view.size() > 100u);
  for (std::size_t n : {view.v.size(), view.m.size(), view.phase.size(), view.id.size(), view.pressure.size(),
                        view.density.size(), view.support.size()})
    BOOST_TEST(n == view.size());
  BOOST_TEST(view.held_water.empty());  // no "porous" section: the optional porous fields stay empty
  BOOST_TEST(view_checksum(view) == run->checksum());
  BOOST_TEST(run->checksum() != initial);  // the water moved
  // A dam break without porous flow neither creates nor destroys water: the mass is exact.
  BOOST_TEST(total_water(view) == water0, boost::test_tools::tolerance(1e-12));
  std::size_t moving = 0;
  for (std::size_t i = 0; i < view.size(); ++i) moving += view.moves(i) ? 1 : 0;
  BOOST_TEST(moving > 0u);
  BOOST_TEST(moving < view.size());  // the tank walls are particles too
  std::vector<std::string> stages;
  for (const StageTime& s : run->stage_times()) {
    stages.push_back(s.name);
    BOOST_TEST(s.seconds >= 0.0);
  }
  BOOST_TEST(std::count(stages.begin(), stages.end(), "neighbours") == 1);
  BOOST_TEST(!run->own_steps().has_value());  // SPH's step is the case step
  BOOST_TEST(run->vtu_frame().ends_with("</VTKFile>\n"));
}

// The pore-water pressure a run shows (ParticleView::pore_water_pressure, the VTU field) is P^p − P^c:
// unsaturated pore water is under suction. A fixed porous bed at S = 0.5 with the capillary
// potential P^c = k^c (1 − S)^α of [thesis eq. 23] (k^c = 500 Pa, α = 0.5) and a permeability too
// small to move water in one step: every bed particle away from its faces shows −k^c (1 − S)^α =
// −353.55 Pa (1e-6) and its saturation 0.5.
BOOST_AUTO_TEST_CASE(an_unsaturated_bed_shows_its_pore_water_under_suction) {
  json doc = small_case_json();
  doc["porous"] = {{"porosity", 0.4}, {"permeability", 1e-16}, {"capillary_constant", 500.0},
                   {"capillary_exponent", 0.5}, {"initial_saturation", 0.5}};
  doc["blocks"] = json::array({{{"phase", "porous_bed"}, {"min", {0.0, 0.0}}, {"max", {0.2, 0.12}}}});
  const std::unique_ptr<Method<2>> run = make_method<2>(load_case(write_case(doc)), kSpacing);
  run->step();
  const ParticleView<2> view = run->particles();
  BOOST_TEST_REQUIRE(view.pore_water_pressure.size() == view.size());
  const double expected = -500.0 * std::sqrt(0.5);
  std::size_t inside = 0, wrong = 0;
  for (std::size_t i = 0; i < view.size(); ++i) {
    if (view.porosity[i] <= 0.0) continue;
    const Vec<2>& x = view.x[i];
    if (x[0] < 0.05 || x[0] > 0.15 || x[1] < 0.04 || x[1] > 0.08) continue;
    ++inside;
    if (std::abs(view.pore_water_pressure[i] / expected - 1.0) > 1e-6 || std::abs(view.saturation[i] - 0.5) > 1e-6) ++wrong;
  }
  BOOST_TEST(inside > 10u);
  BOOST_TEST(wrong == 0u);
}

BOOST_AUTO_TEST_CASE(two_runs_built_through_the_registry_agree_bitwise) {
  const CaseSpec spec = load_case(small_case);
  const std::unique_ptr<Method<2>> a = make_method<2>(spec, kSpacing), b = make_method<2>(spec, kSpacing);
  for (int k = 0; k < 30; ++k) {
    a->step();
    b->step();
  }
  BOOST_TEST(a->checksum() == b->checksum());
  BOOST_TEST(a->time() == b->time());
}

BOOST_AUTO_TEST_CASE(a_run_resumed_through_the_registry_continues_bitwise) {
  const CaseSpec spec = load_case(small_case);
  const std::unique_ptr<Method<2>> straight = make_method<2>(spec, kSpacing);
  BOOST_TEST(straight->writes_checkpoints());
  BOOST_TEST(method_writes_checkpoints("sph"));
  for (int k = 0; k < 20; ++k) straight->step();  // past a neighbour sort (every 16 steps)
  const std::string ckpt = test::fresh_path("method_ckpt", ".ckpt");
  straight->write_checkpoint(ckpt, json{{"marker", 7}});
  json run_log;
  const std::unique_ptr<Method<2>> resumed = resume_method<2>(spec, kSpacing, ckpt, run_log);
  BOOST_TEST(run_log.at("marker") == 7);
  BOOST_TEST(resumed->steps() == 20);
  BOOST_TEST(resumed->checksum() == straight->checksum());
  for (int k = 0; k < 20; ++k) {
    straight->step();
    resumed->step();
  }
  BOOST_TEST(resumed->checksum() == straight->checksum());
  BOOST_TEST(resumed->time() == straight->time());
  // The same checkpoint at another spacing belongs to another run.
  try {
    resume_method<2>(spec, 2.0 * kSpacing, ckpt, run_log);
    BOOST_ERROR("a checkpoint of another spacing was accepted");
  } catch (const InputError& e) {
    BOOST_TEST(e.json_path() == "/spacing");
  }
  fs::remove(ckpt);
}

BOOST_AUTO_TEST_CASE(an_unknown_method_is_rejected_with_the_case_file_and_json_path) {
  json doc = small_case_json();
  doc["method"] = "no_such_method";
  const std::string file = write_case(doc);
  const CaseSpec spec = load_case(file);  // the case's syntax is fine; the name is the registry's to judge
  for (auto build : {+[](const CaseSpec& s) { check_method(s); }, +[](const CaseSpec& s) { make_method<2>(s, kSpacing); }}) {
    try {
      build(spec);
      BOOST_ERROR("an unknown method was accepted");
    } catch (const InputError& e) {
      BOOST_TEST(e.file() == file);
      BOOST_TEST(e.json_path() == "/method");
      BOOST_TEST(e.rule().find("no_such_method") != std::string::npos);
      BOOST_TEST(e.rule().find("\"sph\"") != std::string::npos);  // names what the build knows
    }
  }
  doc["method"] = "sph";
  doc["methods"] = {{"no_such_method", json::object()}};
  try {
    check_method(load_case(write_case(doc)));
    BOOST_ERROR("an unknown method under \"methods\" was accepted");
  } catch (const InputError& e) {
    BOOST_TEST(e.json_path() == "/methods/no_such_method");
  }
  BOOST_TEST(method_names() == (std::vector<std::string>{"sph", "flip", "dem", "mpm"}));
}

BOOST_AUTO_TEST_CASE(method_flag_must_name_a_method_the_case_supports) {
  const CaseSpec spec = load_case(small_case);
  BOOST_TEST(with_method(spec, "").method == "sph");
  BOOST_TEST(with_method(spec, "sph").method == "sph");
  try {
    with_method(spec, "flip");
    BOOST_ERROR("a method the case does not list was accepted");
  } catch (const InputError& e) {
    BOOST_TEST(e.json_path() == "/methods");
    BOOST_TEST(e.rule().find("--method flip") != std::string::npos);
  }
}

BOOST_AUTO_TEST_CASE(the_sph_probe_is_refused_for_a_case_run_by_another_method) {
  CaseSpec spec = load_case(small_case);
  BOOST_CHECK_NO_THROW(require_sph(spec, "a test"));
  spec.method = "flip";
  try {
    require_sph(spec, "a test");
    BOOST_ERROR("the SPH probe was granted to a non-SPH case");
  } catch (const InputError& e) {
    BOOST_TEST(e.json_path() == "/method");
    BOOST_TEST(e.rule().find("a test needs the SPH method") != std::string::npos);
  }
}

BOOST_AUTO_TEST_CASE(sandcastle_run_exits_2_for_an_unknown_method_before_writing) {
  json doc = small_case_json();
  doc["method"] = "no_such_method";
  const std::string file = write_case(doc);
  const std::string out = test::fresh_path("method_out");
  const test::ProcessResult r = test::run_sandcastle({"run", file, "--out", out}, 30.0);
  BOOST_TEST(r.exit_code == 2);
  BOOST_TEST(r.err.find(file + ": /method: unknown method \"no_such_method\"") != std::string::npos, r.err);
  BOOST_TEST(!fs::exists(out));
  const test::ProcessResult flag = test::run_sandcastle({"run", small_case, "--out", out, "--method", "flip"}, 30.0);
  BOOST_TEST(flag.exit_code == 2);
  BOOST_TEST(flag.err.find("/methods: --method flip") != std::string::npos, flag.err);
  BOOST_TEST(!fs::exists(out));
}

// FLIP through the seam (solver/flip/flip_method.hpp): the case's blocks become FLIP particles at
// the case spacing, the run steps, its view shows what its checksum hashes, mass is exact, it
// times its own stages and writes no checkpoints.
BOOST_AUTO_TEST_CASE(a_flip_run_built_through_the_registry_steps) {
  const CaseSpec spec = with_method(load_case(write_case(small_flip_case_json())), "flip");
  const std::unique_ptr<Method<2>> run = make_method<2>(spec, 0.01);
  BOOST_TEST(run->name() == "flip");
  BOOST_TEST(!run->writes_checkpoints());
  BOOST_TEST(!method_writes_checkpoints("flip"));
  const ParticleView<2> start = run->particles();
  BOOST_TEST(start.size() == 200u + 100u);  // 10 x 20 water and 10 x 10 sand at 0.01 m
  double mass0 = 0.0;
  for (std::size_t i = 0; i < start.size(); ++i) mass0 += start.m[i];
  BOOST_TEST(mass0 == 0.1 * 0.2 * 1000.0 + 0.1 * 0.1 * 2650.0, boost::test_tools::tolerance(1e-12));
  const std::string initial = run->checksum();
  for (int k = 0; k < 40; ++k) run->step();
  const ParticleView<2> view = run->particles();
  for (std::size_t n : {view.v.size(), view.m.size(), view.phase.size(), view.pressure.size(), view.density.size(),
                        view.support.size()})
    BOOST_TEST(n == view.size());
  BOOST_TEST(view_checksum(view) == run->checksum());
  BOOST_TEST(run->checksum() != initial);
  double mass = 0.0, p_max = 0.0;
  for (std::size_t i = 0; i < view.size(); ++i) {
    mass += view.m[i];
    p_max = std::max(p_max, view.pressure[i]);
  }
  BOOST_TEST(mass == mass0);  // particles carry their mass unchanged
  // The pressure under the 0.2 m water column is of the order of ρ g H (about 2 kPa).
  BOOST_TEST(p_max > 500.0);
  BOOST_TEST(p_max < 4000.0);
  std::vector<std::string> stages;
  for (const StageTime& s : run->stage_times()) stages.push_back(s.name);
  BOOST_TEST(stages == (std::vector<std::string>{"transfer", "projection", "sand stress", "rigid groups", "advection"}));
  BOOST_TEST(run->vtu_frame().find("Name=\"pressure\"") != std::string::npos);
  BOOST_TEST(run->last_good_frame().ends_with("</VTKFile>\n"));
}

BOOST_AUTO_TEST_CASE(a_flip_run_is_bitwise_the_same_on_one_and_two_threads) {
  const CaseSpec spec = with_method(load_case(write_case(small_flip_case_json())), "flip");
  const int saved = omp_get_max_threads();
  std::string checksum[2];
  for (const int threads : {1, 2}) {
    omp_set_num_threads(threads);
    const std::unique_ptr<Method<2>> run = make_method<2>(spec, 0.01);
    for (int k = 0; k < 40; ++k) run->step();
    checksum[threads - 1] = run->checksum();
  }
  omp_set_num_threads(saved);
  BOOST_TEST(checksum[0] == checksum[1]);
}

BOOST_AUTO_TEST_CASE(an_unknown_flip_parameter_is_rejected_with_its_path) {
  json doc = small_flip_case_json();
  doc["methods"]["flip"]["cell_sise"] = 2.0;
  const std::string file = write_case(doc);
  try {
    check_method(load_case(file));  // the case still runs SPH by default: FLIP's keys are checked all the same
    BOOST_ERROR("an unknown FLIP key was accepted");
  } catch (const InputError& e) {
    BOOST_TEST(e.file() == file);
    BOOST_TEST(e.json_path() == "/methods/flip/cell_sise");
  }
  const std::string out = test::fresh_path("method_out");
  const test::ProcessResult r = test::run_sandcastle({"run", file, "--out", out, "--method", "flip"}, 30.0);
  BOOST_TEST(r.exit_code == 2);
  BOOST_TEST(r.err.find("/methods/flip/cell_sise") != std::string::npos, r.err);
  BOOST_TEST(!fs::exists(out));
  doc = small_flip_case_json();
  doc["methods"]["flip"]["cell_size"] = 3.0;  // 0.4 m is not a whole number of 0.03 m cells
  try {
    make_method<2>(with_method(load_case(write_case(doc)), "flip"), 0.01);
    BOOST_ERROR("a tank that is not a whole number of cells was accepted");
  } catch (const InputError& e) {
    BOOST_TEST(e.json_path() == "/methods/flip/cell_size");
  }
}

// MPM through the seam (solver/mpm/mpm_method.hpp): water and sand blocks become MPM particles at
// the case spacing, the run steps in substeps, its view shows what its checksum hashes, mass is
// exact, the water under the column is at about ρ g H, it times its four stages and is bitwise the
// same on one and two threads; a misspelt key of "methods"/"mpm" is named with its path.
BOOST_AUTO_TEST_CASE(an_mpm_run_built_through_the_registry_steps) {
  const CaseSpec spec = with_method(load_case(write_case(small_mpm_case_json())), "mpm");
  const int saved = omp_get_max_threads();
  std::string checksum[2];
  for (const int threads : {1, 2}) {
    omp_set_num_threads(threads);
    const std::unique_ptr<Method<2>> run = make_method<2>(spec, 0.01);
    BOOST_TEST(run->name() == "mpm");
    BOOST_TEST(!run->writes_checkpoints());
    BOOST_TEST(!method_writes_checkpoints("mpm"));
    const ParticleView<2> start = run->particles();
    BOOST_TEST(start.size() == 200u + 100u);
    double mass0 = 0.0;
    for (std::size_t i = 0; i < start.size(); ++i) mass0 += start.m[i];
    BOOST_TEST(mass0 == 0.1 * 0.2 * 1000.0 + 0.1 * 0.1 * 2650.0, boost::test_tools::tolerance(1e-12));
    for (int k = 0; k < 40; ++k) run->step();
    const ParticleView<2> view = run->particles();
    for (std::size_t n : {view.v.size(), view.m.size(), view.phase.size(), view.pressure.size(), view.density.size(),
                          view.support.size(), view.saturation.size()})
      BOOST_TEST(n == view.size());
    BOOST_TEST(view_checksum(view) == run->checksum());
    double mass = 0.0, p_max = 0.0;
    for (std::size_t i = 0; i < view.size(); ++i) {
      mass += view.m[i];
      if (view.phase_of(i) == Phase::Water) p_max = std::max(p_max, view.pressure[i]);
    }
    BOOST_TEST(mass == mass0);
    BOOST_TEST(p_max > 500.0);
    BOOST_TEST(p_max < 4000.0);
    std::vector<std::string> stages;
    long substeps = 0;
    for (const StageTime& st : run->stage_times()) {
      stages.push_back(st.name);
      substeps += st.count;
    }
    BOOST_TEST(stages == (std::vector<std::string>{"transfer", "stress", "grid", "exchange"}));
    BOOST_TEST(substeps >= 40);
    BOOST_TEST(run->own_steps().value() == substeps);  // bench's own steps: the MPM steps
    BOOST_TEST(run->vtu_frame().find("Name=\"saturation\"") != std::string::npos);
    checksum[threads - 1] = run->checksum();
  }
  omp_set_num_threads(saved);
  BOOST_TEST(checksum[0] == checksum[1]);
  json doc = small_mpm_case_json();
  doc["methods"]["mpm"]["porosty"] = 0.4;
  const std::string file = write_case(doc);
  try {
    check_method(load_case(file));
    BOOST_ERROR("an unknown MPM key was accepted");
  } catch (const InputError& e) {
    BOOST_TEST(e.file() == file);
    BOOST_TEST(e.json_path() == "/methods/mpm/porosty");
  }
  const std::string out = test::fresh_path("method_out");
  const test::ProcessResult r = test::run_sandcastle({"run", file, "--out", out, "--method", "mpm"}, 30.0);
  BOOST_TEST(r.exit_code == 2);
  BOOST_TEST(r.err.find("/methods/mpm/porosty") != std::string::npos, r.err);
  BOOST_TEST(!fs::exists(out));
}

// MPM's seeding (make_mpm_method): each block is tiled by squares of side dx with one particle at
// the centre of each, so the particles stand dx/2 inside every face of their block and their centre
// of mass is the block's centre. The small MPM case at dx = 0.01 m: the water block [0, 0.1] x
// [0, 0.2] holds 200 particles from (0.005, 0.005) to (0.095, 0.195), centred on (0.05, 0.1); the
// sand block [0.2, 0.3] x [0, 0.1] holds 100 from (0.205, 0.005) to (0.295, 0.095), centred on
// (0.25, 0.05) (1e-12 m).
BOOST_AUTO_TEST_CASE(mpm_seeds_each_block_at_the_centres_of_its_lattice_squares) {
  const CaseSpec spec = with_method(load_case(write_case(small_mpm_case_json())), "mpm");
  const double dx = 0.01;
  const std::unique_ptr<Method<2>> run = make_method<2>(spec, dx);
  const ParticleView<2> view = run->particles();
  const std::array<Phase, 2> phases{Phase::Water, Phase::Sand};
  const std::array<std::array<double, 4>, 2> blocks{{{0.0, 0.0, 0.1, 0.2}, {0.2, 0.0, 0.3, 0.1}}};  // lo, hi
  const std::array<std::size_t, 2> counts{200u, 100u};
  for (int b = 0; b < 2; ++b) {
    BOOST_TEST_CONTEXT("block " << b) {
      const Vec<2> lo(blocks[b][0], blocks[b][1]), hi(blocks[b][2], blocks[b][3]);
      std::size_t n = 0;
      Vec<2> sum = Vec<2>::Zero(), first = Vec<2>::Constant(INFINITY), last = Vec<2>::Constant(-INFINITY);
      for (std::size_t i = 0; i < view.size(); ++i) {
        if (view.phase_of(i) != phases[b]) continue;
        ++n;
        sum += view.x[i];
        first = first.cwiseMin(view.x[i]);
        last = last.cwiseMax(view.x[i]);
      }
      BOOST_TEST(n == counts[b]);
      BOOST_TEST((sum / static_cast<double>(n) - 0.5 * (lo + hi)).norm() <= 1e-12);
      BOOST_TEST((first - (lo + Vec<2>::Constant(0.5 * dx))).norm() <= 1e-12);
      BOOST_TEST((last - (hi - Vec<2>::Constant(0.5 * dx))).norm() <= 1e-12);
    }
  }
}

// A porous bed under MPM takes the case's "porous" section as Tampubolon et al. 2017 use it
// (darcy_column, its bed filled to half saturation, 0.01 m):
// - its pores hold ρ_w n S of the bed's volume as water particles on the bed's sites, to round-off;
// - the drag c_E resists a seepage at Darcy's flux q = (k/μ) ρ_w g i, of permeability k and fluid
//   viscosity μ, with the water's share of the head gradient, c_E q/n = n ρ_w g i [Tampubolon 2017:
//   drag c_E], to round-off.
BOOST_AUTO_TEST_CASE(an_mpm_bed_holds_its_pore_water_and_drags_it_by_darcys_law) {
  std::ifstream in(std::string(SANDCASTLE_SOURCE_DIR) + "/cases/darcy_column/case.json");
  json doc = json::parse(in);
  doc["porous"]["initial_saturation"] = 0.5;
  const CaseSpec spec = with_method(load_case(write_case(doc)), "mpm");
  const double dx = 0.01, n = 0.4, S = 0.5, rho_w = 1000.0, g = 9.81;
  const std::unique_ptr<Method<2>> run = make_method<2>(spec, dx);
  const ParticleView<2> view = run->particles();
  double pore_water = 0.0;
  for (std::size_t i = 0; i < view.size(); ++i)
    if (view.phase_of(i) == Phase::Water && view.x[i][1] < 0.5) pore_water += view.m[i];
  BOOST_TEST(pore_water == rho_w * n * S * 0.2 * 0.3, boost::test_tools::tolerance(1e-12));
  const double k = 2.04e-9, mu = 1e-3, i = 0.5;
  const double q = k / mu * rho_w * g * i;
  const double drag = mpm_params<2>(spec, read_mpm_params(spec), dx).drag;
  BOOST_TEST(drag * q / n == n * rho_w * g * i, boost::test_tools::tolerance(1e-12));
}

// DEM through the seam (solver/dem/dem_method.hpp): the column packed in its mould weighs ρ L H, the grains fall onto the floor and push no deeper than
// the overlap the stiffness was set for, the run times its contact steps and is the same bitwise on
// one and two threads.
BOOST_AUTO_TEST_CASE(a_dem_run_built_through_the_registry_settles_on_its_springs) {
  const CaseSpec spec = with_method(load_case(write_case(small_dem_case_json())), "dem");
  const int saved = omp_get_max_threads();
  std::string checksum[2];
  for (const int threads : {1, 2}) {
    omp_set_num_threads(threads);
    const std::unique_ptr<Method<2>> run = make_method<2>(spec, 0.01);
    BOOST_TEST(run->name() == "dem");
    BOOST_TEST(!method_writes_checkpoints("dem"));
    double mass = 0.0;
    for (std::size_t i = 0; i < run->particles().size(); ++i) mass += run->particles().m[i];
    BOOST_TEST(run->particles().size() > 80u);  // the poured column: about one grain per 0.01 m site
    BOOST_TEST(run->particles().size() < 120u);
    BOOST_TEST(mass == 0.1 * 0.1 * 2650.0, boost::test_tools::tolerance(1e-12));
    for (int k = 0; k < 1000; ++k) run->step();
    const ParticleView<2> view = run->particles();
    BOOST_TEST(view_checksum(view) == run->checksum());
    double lowest = INFINITY;
    for (std::size_t i = 0; i < view.size(); ++i) lowest = std::min(lowest, view.x[i][1] - view.support[i]);
    BOOST_TEST_MESSAGE("lowest " << lowest);
    BOOST_TEST(lowest < 0.0);                   // resting on the floor's spring
    BOOST_TEST(lowest > -0.01 * 0.5 * 0.01);    // by less than 1 % of the grain radius
    BOOST_TEST(run->stage_times().front().count > 200);  // several contact steps per case step
    BOOST_TEST(run->own_steps().value() == run->stage_times().front().count);  // bench's own steps
    run->reset_stage_times();
    BOOST_TEST(run->own_steps().value() == 0);
    checksum[threads - 1] = run->checksum();
  }
  omp_set_num_threads(saved);
  BOOST_TEST(checksum[0] == checksum[1]);
}

BOOST_AUTO_TEST_CASE(a_dem_case_with_a_porous_bed_or_a_bad_parameter_is_rejected_with_its_path) {
  json doc = small_dem_case_json();
  doc["methods"]["dem"]["restitution"] = 0.0;
  try {
    check_method(load_case(write_case(doc)));
    BOOST_ERROR("restitution 0 was accepted");
  } catch (const InputError& e) {
    BOOST_TEST(e.json_path() == "/methods/dem/restitution");
  }
  doc = small_dem_case_json();
  doc["porous"] = {{"porosity", 0.4}, {"permeability", 1e-9}};
  doc["blocks"].push_back({{"phase", "porous_bed"}, {"min", {0.2, 0.0}}, {"max", {0.3, 0.1}}});
  try {
    check_method(load_case(write_case(doc)));
    BOOST_ERROR("a porous_bed block was accepted for DEM");
  } catch (const InputError& e) {
    BOOST_TEST(e.json_path() == "/blocks/1/phase");
  }
}

BOOST_AUTO_TEST_SUITE_END()
