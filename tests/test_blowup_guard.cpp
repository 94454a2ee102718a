// The blow-up guard's copy (Simulator::last_good) is the state at the start of the last step (after
// its storage sort, if it sorts), field for field, bit for bit, although it copies only what a step
// can change (ParticleSet::refresh_from).
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cstring>
#include <numeric>
#include <optional>
#include <utility>

#include "case/case_file.hpp"
#include "scene/scene_builder.hpp"
#include "simulator/simulator.hpp"

using namespace sc;

namespace {

/// Whether every field of a and b holds the same bytes.
template <int D>
bool same_bits(const ParticleSet<D>& a, const ParticleSet<D>& b) {
  bool same = a.size() == b.size();
  a.visit_fields([&](std::string_view name, const auto& field) {
    b.visit_fields([&](std::string_view other_name, const auto& other) {
      if constexpr (std::is_same_v<std::decay_t<decltype(field)>, std::decay_t<decltype(other)>>)
        if (name == other_name && (field.size() != other.size() ||
                                   std::memcmp(field.data(), other.data(), field.size() * sizeof(field[0])) != 0)) {
          BOOST_TEST_MESSAGE("field " << name << " differs");
          same = false;
        }
    });
  });
  return same;
}

/// `ps` with its particles in the order of their ids (unique).
template <int D>
ParticleSet<D> in_id_order(ParticleSet<D> ps) {
  std::vector<std::size_t> order(ps.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return ps.id[a] < ps.id[b]; });
  ps.permute(order);
  return ps;
}

/// Runs `steps` steps of a case at its quick spacing; after each, last_good() must equal the state
/// before it, and in its order except in a step that begins with a storage sort (every
/// Simulator::kSortEvery = 16 steps), where the guard keeps the sorted state: the same particles,
/// bit for bit, relabelled. Over 40 steps, steps with and without sorting are both seen.
template <int D>
void check_guard(const std::string& path, int steps) {
  const CaseSpec spec = load_case(path);
  const double dx = spec.tiers.at("quick").spacings.front();
  Simulator<D> sim(build_scene<D>(spec, dx), SimulationParams::from_case(spec, dx));
  for (int k = 0; k < steps; ++k) {
    ParticleSet<D> before = std::as_const(sim).particles();
    sim.step();
    BOOST_TEST_CONTEXT(path << " step " << k + 1) {
      if (k % 16 == 0) BOOST_TEST(same_bits<D>(in_id_order(sim.last_good()), in_id_order(std::move(before))));
      else BOOST_TEST(same_bits<D>(sim.last_good(), before));
    }
  }
  // Only a porous scene carries the porous-flow fields, through splits, merges and emissions.
  BOOST_TEST(sim.particles().has_porous_fields() == spec.porous.has_value());
  BOOST_TEST(sim.last_good().has_porous_fields() == spec.porous.has_value());
}

/// The blow-up that the next step of `sim` throws, if it throws one.
template <int D>
std::optional<BlowUpError> blow_up_of_next_step(Simulator<D>& sim) {
  try {
    sim.step();
  } catch (const BlowUpError& e) {
    return e;
  }
  return std::nullopt;
}

/// The small dam break at its quick spacing after one ordinary step.
Simulator<2> dam_after_one_step() {
  const CaseSpec spec = load_case(std::string(SANDCASTLE_SOURCE_DIR) + "/tests/reliability/small_dam_break.json");
  const double dx = spec.tiers.at("quick").spacings.front();
  Simulator<2> sim(build_scene<2>(spec, dx), SimulationParams::from_case(spec, dx));
  sim.step();
  return sim;
}

/// Checks that the runaway blow-up `e` stops step 2 at particle 0, its diagnostic saying `said`.
void check_runaway_at_step_2_of_particle_0(const BlowUpError& e, const std::string& said) {
  BOOST_TEST(e.step() == 2);
  BOOST_TEST(e.particle() == 0);
  BOOST_TEST(std::string(e.what()).find(said) != std::string::npos, e.what());
}

}  // namespace

BOOST_AUTO_TEST_SUITE(blowup_guard)

BOOST_AUTO_TEST_CASE(last_good_is_the_state_before_the_step) {
  // Sand, porous water, rough and slip walls, rigid clusters; then split and merge (adaptive), whose
  // density offsets decay at the walls too.
  const std::string root = SANDCASTLE_SOURCE_DIR;
  check_guard<2>(root + "/cases/wet_sand_collapse/case.json", 40);
  check_guard<2>(root + "/tests/reliability/small_dam_break_adaptive.json", 40);
}

// A speed that runs away shrinks the CFL step without end; the run must stop as a blow-up
// (core/errors.hpp kShortestStepFraction) instead of stalling. Particle 0 (the first moving one in
// storage, a water particle of the dam) is set to 1e6 m/s after one ordinary step: the next step
// would be 0.4 (0.01 m) / (1e6 m/s) = 4e-9 s, below 1e-4 of the case's 1 ms, so step 2 stops before
// it moves anything. At 100 m/s (3.5e-5 s) the step runs.
BOOST_AUTO_TEST_CASE(a_runaway_speed_stops_the_step_as_a_blow_up) {
  for (const double speed : {100.0, 1e6}) {
    Simulator<2> sim = dam_after_one_step();
    BOOST_TEST_REQUIRE((sim.particles().phase_of(0) == Phase::Water));
    sim.particles().v[0] = Vec<2>(speed, 0.0);
    BOOST_TEST_CONTEXT("speed " << speed << " m/s") {
      const std::optional<BlowUpError> e = blow_up_of_next_step(sim);
      BOOST_TEST(e.has_value() == (speed > 1e3));
      if (!e) continue;
      check_runaway_at_step_2_of_particle_0(*e, "field 'velocity': a speed of 1e+06 m/s");
      BOOST_TEST(sim.particles().v[0][0] == speed);  // the last good state, from before the step
    }
  }
}

// The force condition 0.25 sqrt(spacing / a) shrinks the step too: below 1e-4 of the case's 1 ms at
// the 0.01 m spacing once an acceleration exceeds 0.01 / (16 (1e-7 s)^2) = 6.25e10 m/s^2. Particle
// 1, a lattice neighbour of particle 0 in the dam, is made 1e13 times heavier after one ordinary
// step: its summed density, and with it its Tait pressure, become so large that the pressure force
// pushes particle 0, still nearly at rest, far beyond that, so step 2 stops before it moves anything
// and names particle 0 and its force. Made twice as heavy, the step runs.
BOOST_AUTO_TEST_CASE(a_runaway_force_stops_the_step_as_a_blow_up) {
  for (const double factor : {2.0, 1e13}) {
    Simulator<2> sim = dam_after_one_step();
    const auto& ps = std::as_const(sim).particles();
    BOOST_TEST_REQUIRE((ps.phase_of(0) == Phase::Water && ps.phase_of(1) == Phase::Water));
    BOOST_TEST_REQUIRE((ps.x[1] - ps.x[0]).norm() < 0.5 * ps.h[0]);
    const Vec<2> x0 = ps.x[0];
    sim.particles().m[1] *= factor;
    BOOST_TEST_CONTEXT("mass x " << factor) {
      const std::optional<BlowUpError> e = blow_up_of_next_step(sim);
      BOOST_TEST(e.has_value() == (factor > 1e3));
      if (!e) continue;
      check_runaway_at_step_2_of_particle_0(*e, "field 'force': an acceleration of");
      BOOST_TEST((sim.particles().x[0] == x0));  // the last good state, from before the step
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()
