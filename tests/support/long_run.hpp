// A precondition for the test cases that run a long simulation (many steps, several processes):
// the sanitizer build (SANDCASTLE_SANITIZE, tools/sanitize.sh), where a step runs about ten times
// slower, skips them and names the reason; every other build runs them, the README's test command
// among them. The short cases of the same suite reach the same code under the sanitizers.
//
//   BOOST_AUTO_TEST_CASE(name, *sc::test::long_run()) { ... }
#pragma once
#include <boost/test/unit_test.hpp>

namespace sc::test {

inline boost::test_tools::assertion_result not_sanitized(boost::unit_test::test_unit_id) {
#ifdef SANDCASTLE_SANITIZED
  boost::test_tools::assertion_result run(false);
  run.message() << "a long run: skipped in the sanitizer build, run by the Release build's tests";
  return run;
#else
  return true;
#endif
}

inline boost::unit_test::precondition long_run() { return boost::unit_test::precondition(&not_sanitized); }

}  // namespace sc::test
