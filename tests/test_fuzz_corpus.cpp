// Replays the fuzzers' seed corpora (tests/fuzz/corpus/<target>/) through the loaders they fuzz:
// every input must load or be refused with an InputError. An input that once crashed a fuzzer
// is added there, so this suite is also the regression test for what fuzzing found.
#include <boost/test/unit_test.hpp>
#include <filesystem>

#include "geometry/triangle_mesh.hpp"
#include "case/case_file.hpp"

namespace fs = std::filesystem;
using namespace sc;

namespace {

const fs::path corpus_root = fs::path(SANDCASTLE_SOURCE_DIR) / "tests" / "fuzz" / "corpus";

/// Runs `load` on every file of the corpus folder; returns how many loaded without error.
template <class Load>
int replay(const std::string& target, Load load) {
  int loaded = 0, files = 0;
  for (const auto& entry : fs::directory_iterator(corpus_root / target)) {
    ++files;
    try {
      load(entry.path().string());
      ++loaded;
    } catch (const InputError&) {
    } catch (const std::exception& e) {
      BOOST_ERROR(entry.path().filename() << ": not an InputError: " << e.what());
    }
  }
  BOOST_TEST(files > 0);
  return loaded;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(fuzz_corpus)

BOOST_AUTO_TEST_CASE(case_loader_corpus_loads_or_is_refused_cleanly) {
  BOOST_TEST(replay("case_loader", [](const std::string& f) { load_case(f); }) > 0);
}

BOOST_AUTO_TEST_CASE(obj_loader_corpus_loads_or_is_refused_cleanly) {
  BOOST_TEST(replay("obj_loader", [](const std::string& f) { require_closed(load_obj(f), f); }) > 0);
}

BOOST_AUTO_TEST_SUITE_END()
