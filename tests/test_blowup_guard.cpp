// The blow-up guard's copy (Simulator::last_good) is the state at the start of the last step (after
// its storage sort, if it sorts), field for field, bit for bit, although it copies only what a step
// can change (ParticleSet::refresh_from).
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cstring>
#include <numeric>
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

}  // namespace

BOOST_AUTO_TEST_SUITE(blowup_guard)

BOOST_AUTO_TEST_CASE(last_good_is_the_state_before_the_step) {
  // Sand, porous water, rough and slip walls, rigid clusters; then split and merge (adaptive), whose
  // density offsets decay at the walls too.
  const std::string root = SANDCASTLE_SOURCE_DIR;
  check_guard<2>(root + "/cases/wet_sand_collapse/case.json", 40);
  check_guard<2>(root + "/tests/reliability/small_dam_break_adaptive.json", 40);
}

BOOST_AUTO_TEST_SUITE_END()
