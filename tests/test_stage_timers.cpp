// StageTimers: nested scopes count every instant in exactly one stage.
#include <boost/test/unit_test.hpp>

#include <chrono>
#include <thread>

#include "core/stage_timers.hpp"

using namespace sc;
using namespace std::chrono_literals;

BOOST_AUTO_TEST_SUITE(stage_timers)

BOOST_AUTO_TEST_CASE(nested_scope_pauses_the_outer_stage) {
  StageTimers t;
  const auto start = std::chrono::steady_clock::now();
  {
    auto outer = t.time(Stage::Integration);
    std::this_thread::sleep_for(20ms);
    {
      auto inner = t.time(Stage::Clusters);
      std::this_thread::sleep_for(40ms);
    }
    std::this_thread::sleep_for(20ms);
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double inner = t.seconds(Stage::Clusters), outer = t.seconds(Stage::Integration);
  BOOST_TEST(inner >= 0.040);
  BOOST_TEST(outer >= 0.040);
  // Exclusive: the two stages add up to the elapsed time (a nested timer that also ran the outer
  // clock would give outer >= inner + 40 ms and a sum of at least wall + 40 ms).
  BOOST_TEST(inner + outer <= wall);
  BOOST_TEST(inner + outer >= wall - 0.005);
  BOOST_TEST(t.seconds(Stage::Forces) == 0.0);
}

BOOST_AUTO_TEST_CASE(scopes_after_a_nested_one_keep_counting) {
  StageTimers t;
  {
    auto outer = t.time(Stage::Integration);
    { auto inner = t.time(Stage::Clusters); }
    std::this_thread::sleep_for(30ms);  // after the inner scope closed: the outer stage again
  }
  std::this_thread::sleep_for(100ms);  // no scope open: counted nowhere
  BOOST_TEST(t.seconds(Stage::Integration) >= 0.030);
  BOOST_TEST(t.seconds(Stage::Integration) < 0.100);  // 30 ms (and the sleep's overshoot), not 130 ms
  t.reset();
  BOOST_TEST(t.seconds(Stage::Integration) == 0.0);
}

BOOST_AUTO_TEST_SUITE_END()
