// The bad-input corpus (tests/bad_inputs/manifest.json): every entry runs the real `sandcastle`
// command on a malformed case file, checkpoint or command line and must get exit code 2, a message
// naming the file, the JSON path and the rule broken, no crash, no hang, and no output written.
#include <boost/test/unit_test.hpp>
#include <set>

#include "io/json_reader.hpp"
#include "support/process.hpp"

namespace fs = std::filesystem;
using namespace sc;

namespace {

const std::string corpus_dir = std::string(SANDCASTLE_SOURCE_DIR) + "/tests/bad_inputs";
const std::string valid_case = std::string(SANDCASTLE_SOURCE_DIR) + "/tests/reliability/small_dam_break.json";

/// The argument with its placeholders {dir}, {out} and {valid} replaced.
std::string expand(std::string arg, const std::string& out) {
  for (const auto& [key, value] : {std::pair<std::string, std::string>{"{dir}", corpus_dir}, {"{out}", out},
                                   {"{valid}", valid_case}})
    for (auto k = arg.find(key); k != std::string::npos; k = arg.find(key)) arg.replace(k, key.size(), value);
  return arg;
}

json corpus() { return read_json_file(corpus_dir + "/manifest.json").at("cases"); }

}  // namespace

BOOST_AUTO_TEST_SUITE(bad_inputs)

BOOST_AUTO_TEST_CASE(corpus_has_thirty_distinct_entries) {
  std::set<std::string> names;
  for (const json& entry : corpus()) names.insert(entry.at("name").get<std::string>());
  BOOST_TEST(names.size() == corpus().size());
  BOOST_TEST(names.size() >= 30u);
}

BOOST_AUTO_TEST_CASE(every_entry_exits_2_with_its_message_and_writes_nothing) {
  for (const json& entry : corpus()) {
    const std::string name = entry.at("name");
    const std::string out = test::fresh_path("bad_input_out");
    std::vector<std::string> args;
    for (const json& a : entry.at("args")) args.push_back(expand(a.get<std::string>(), out));
    const test::ProcessResult r = test::run_sandcastle(args, 30.0);
    BOOST_TEST_CONTEXT("corpus entry " << name << ", stderr: " << r.err) {
      BOOST_TEST(!r.timed_out);
      BOOST_TEST(r.signal == 0);
      BOOST_TEST(r.exit_code == 2);
      for (const json& expected : entry.at("expect"))
        BOOST_TEST(r.err.find(expected.get<std::string>()) != std::string::npos, "expected message part: " << expected);
      BOOST_TEST(!fs::exists(out), "bad input must not create the output folder");
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()
