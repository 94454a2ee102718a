// End-to-end reliability of `sandcastle run` (the real command): the blow-up guard (exit 3, a
// diagnostic naming step and particle, the last good state as a checkpoint), checkpoint/restart
// ending bitwise equal to an uninterrupted run, crash-safe output under SIGKILL, and a state
// checksum independent of the OpenMP thread count.
#include <boost/test/unit_test.hpp>

#include "io/checkpoint.hpp"
#include "io/json_reader.hpp"
#include "support/pattern.hpp"
#include "support/process.hpp"

namespace fs = std::filesystem;
using namespace sc;

namespace {

const std::string cases_dir = std::string(SANDCASTLE_SOURCE_DIR) + "/tests/reliability";
const std::string small_case = cases_dir + "/small_dam_break.json";  // 824 steps at its quick spacing
const std::string adaptive_case = cases_dir + "/small_dam_break_adaptive.json";  // the same, splitting and merging

/// The newest checkpoint_<step>.ckpt in `dir` (complete files only), or "" if none.
std::string newest_checkpoint(const std::string& dir) {
  std::string newest;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("checkpoint_", 0) == 0 && name.size() == 24 && name.ends_with(".ckpt") && name > newest)
      newest = name;
  }
  return newest.empty() ? newest : dir + "/" + newest;
}

/// A file left by a run must be complete: documents end with their closing tag, checkpoints
/// verify (checksum), JSON parses. Unfinished temporary files (*.tmp.*) are allowed; no reader opens them.
void check_complete(const fs::path& file) {
  const std::string name = file.filename().string();
  if (name.find(".tmp.") != std::string::npos) return;
  const std::string text = test::read_text(file.string());
  BOOST_TEST_CONTEXT("file " << name) {
    if (name.ends_with(".vtu") || name.ends_with(".pvd")) BOOST_TEST(text.ends_with("</VTKFile>\n"));
    else if (name.ends_with(".ckpt")) BOOST_CHECK_NO_THROW(read_checkpoint(file.string()));
    else if (name.ends_with(".json")) BOOST_TEST(json::accept(text));
    else BOOST_ERROR("unexpected file");
  }
}

/// Every frame frames.pvd lists exists.
void check_frames_listed_exist(const std::string& dir) {
  const std::string pvd = test::read_text(dir + "/frames.pvd");
  const std::vector<std::string> listed = test::Pattern("file=\"([^\"]+)\"").every_in(pvd);
  for (const std::string& frame : listed) BOOST_TEST(fs::exists(dir + "/" + frame), frame << " listed in frames.pvd");
  BOOST_TEST(!listed.empty());
}

/// True if a file is being written in `dir` (a temporary *.tmp.* file exists).
bool writing(const std::string& dir) {
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().find(".tmp.") != std::string::npos) return true;
  return false;
}

/// Starts `sandcastle run` on the small case in `out` (resuming from its newest checkpoint, if
/// any) and kills it with SIGKILL once it has written the checkpoint of step `kill_at`.
void run_and_kill(const std::string& out, long kill_at) {
  std::vector<std::string> args{"run", small_case, "--out", out, "--checkpoint-every", "5"};  // writes often
  if (fs::exists(out) && !newest_checkpoint(out).empty()) args.insert(args.end(), {"--resume", newest_checkpoint(out)});
  test::Child child(args, {"OMP_NUM_THREADS=1"});
  const char* name_format = "/checkpoint_%08ld.ckpt";
  char target[32];
  std::snprintf(target, sizeof target, name_format, kill_at);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (!fs::exists(out + target) && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  // Aim the kill at a moment a file is being written, for a short while only: the whole run takes
  // well under 1 s (a checkpoint every 5 steps is a few ms apart), so a long aim can outlast the
  // 174 steps after the last kill, and the run would end before the kill.
  const auto aim_until = std::chrono::steady_clock::now() + std::chrono::milliseconds(20);
  while (!writing(out) && std::chrono::steady_clock::now() < aim_until) {
  }
  child.kill(SIGKILL);
  const test::ProcessResult r = child.wait(30.0);
  BOOST_TEST(r.signal == SIGKILL, "the run ended before it was killed (exit " << r.exit_code << ")");
}

}  // namespace

BOOST_AUTO_TEST_SUITE(reliability)

BOOST_AUTO_TEST_CASE(unstable_case_stops_with_exit_3_naming_step_and_particle) {
  const std::string out = test::fresh_path("unstable");
  const test::ProcessResult r = test::run_sandcastle({"run", cases_dir + "/unstable_step.json", "--out", out});
  BOOST_TEST(r.exit_code == 3);
  const auto m = test::Pattern(R"(blow-up at step (\d+), t = [0-9.e+-]+ s, particle (\d+) \((water|sand|boundary)\), field '(\w+)')")
                     .first_in(r.err);
  BOOST_TEST_REQUIRE(m.has_value(), "diagnostic: " << r.err);
  const Checkpoint last_good = read_checkpoint(out + "/last_good.ckpt");
  BOOST_TEST(last_good.state.step == std::stol(m->at(0)) - 1);  // the state before the failing step
  BOOST_TEST(fs::exists(out + "/last_good.vtu"));
  BOOST_TEST(r.err.find(out + "/last_good.ckpt") != std::string::npos);
}

namespace {

/// Runs `case_file` once through and once resumed from its step-300 checkpoint; returns the
/// uninterrupted and the resumed output folders after checking that both end with one checksum.
std::pair<std::string, std::string> run_and_resume(const std::string& case_file) {
  const std::string full = test::fresh_path("full"), resumed = test::fresh_path("resumed");
  const test::ProcessResult a = test::run_sandcastle({"run", case_file, "--out", full, "--checkpoint-every", "100"});
  BOOST_TEST_REQUIRE(a.exit_code == 0, a.err);
  const test::ProcessResult b = test::run_sandcastle(
      {"run", case_file, "--out", resumed, "--checkpoint-every", "100", "--resume", full + "/checkpoint_00000300.ckpt"});
  BOOST_TEST_REQUIRE(b.exit_code == 0, b.err);
  BOOST_TEST(test::printed_checksum(a.out).size() == 16u);
  BOOST_TEST(test::printed_checksum(a.out) == test::printed_checksum(b.out));
  return {full, resumed};
}

/// Checksums of three runs of `case_file` with 1, 2 and 2 threads.
std::vector<std::string> checksums_by_threads(const std::string& case_file) {
  std::vector<std::string> sums;
  for (const char* threads : {"1", "2", "2"}) {
    const test::ProcessResult r = test::run_sandcastle({"run", case_file, "--out", test::fresh_path("threads")}, 300.0,
                                                       {std::string("OMP_NUM_THREADS=") + threads, "OMP_WAIT_POLICY=passive"});
    BOOST_TEST(r.exit_code == 0, r.err);
    sums.push_back(test::printed_checksum(r.out));
  }
  return sums;
}

}  // namespace

BOOST_AUTO_TEST_CASE(resumed_run_ends_bitwise_equal_to_the_uninterrupted_run) {
  const auto [full, resumed] = run_and_resume(small_case);
  // Every particle field, the clock and the frame log: the last checkpoints are byte-identical.
  const std::string last = fs::path(newest_checkpoint(full)).filename().string();
  BOOST_TEST(std::stol(last.substr(std::string("checkpoint_").size(), 8)) > 300);  // written after the resume
  BOOST_TEST(test::read_text(full + "/" + last) == test::read_text(resumed + "/" + last));
  BOOST_TEST(test::read_text(full + "/final.vtu") == test::read_text(resumed + "/final.vtu"));
}

BOOST_AUTO_TEST_CASE(sigkill_leaves_only_complete_files_and_the_run_resumes) {
  const test::ProcessResult reference = test::run_sandcastle({"run", small_case, "--out", test::fresh_path("ref")});
  BOOST_TEST_REQUIRE(reference.exit_code == 0, reference.err);
  const std::string out = test::fresh_path("killed");
  for (long kill_at : {150, 400, 650}) {  // the same folder, killed three times, resumed in between
    run_and_kill(out, kill_at);
    int temporaries = 0;
    for (const auto& e : fs::directory_iterator(out)) {
      check_complete(e.path());
      temporaries += e.path().filename().string().find(".tmp.") != std::string::npos;
    }
    BOOST_TEST_MESSAGE("killed at step >= " << kill_at << ": " << temporaries << " unfinished *.tmp.* file(s) left");
    check_frames_listed_exist(out);
  }
  const test::ProcessResult last = test::run_sandcastle({"run", small_case, "--out", out, "--resume", newest_checkpoint(out)});
  BOOST_TEST_REQUIRE(last.exit_code == 0, last.err);
  BOOST_TEST(test::printed_checksum(last.out) == test::printed_checksum(reference.out));
  check_frames_listed_exist(out);
}

BOOST_AUTO_TEST_CASE(state_checksum_is_independent_of_thread_count_and_repeatable) {
  for (const std::string& case_file : {small_case, adaptive_case}) {
    BOOST_TEST_CONTEXT(case_file) {
      const std::vector<std::string> sums = checksums_by_threads(case_file);
      BOOST_TEST(sums[0].size() == 16u);
      BOOST_TEST(sums[0] == sums[1]);
      BOOST_TEST(sums[1] == sums[2]);
    }
  }
}

// Splits and merges create and delete particles (fresh ids, density offsets): a resumed adaptive
// run must still end bitwise equal to the uninterrupted one.
BOOST_AUTO_TEST_CASE(adaptive_run_resumes_bitwise) {
  const auto [full, resumed] = run_and_resume(adaptive_case);
  BOOST_TEST(test::read_text(full + "/final.vtu") == test::read_text(resumed + "/final.vtu"));
}

BOOST_AUTO_TEST_SUITE_END()
