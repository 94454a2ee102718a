// One SPH scene decomposed over MPI ranks (solver/parallel/decomposition.hpp, docs/scaling.md):
// `mpirun -n N sandcastle run` gives bitwise the one-process run (state checksum and final frame)
// at 2 and 3 ranks while particles migrate and the slabs are rebalanced, of water and of sand
// (frictional stress, rigid clusters with members on several ranks), a checkpoint of 3 ranks
// resumes on 2 with the uninterrupted checksum, `bench` reports the halo's share, a file rank 0
// cannot write ends every rank with the error, and a case with a feature that is not decomposed
// stops with exit code 2 before it starts. Porous flow through fixed beds (absorption at the pond,
// emission at the seepage face, both next to a slab's border) gives the one-process state too, so
// does wet sand (moving porous sand absorbing water next to a slab's border, its checkpoint of 3
// ranks resuming on 2), and the keys after a compaction are the one-process indices. Adaptive
// sampling (splits and merges next to a slab's border, passes on the gathered scene) gives the
// one-process state and checkpoint, also beside wet sand; a blow-up in a step that sorts or that
// has an adaptivity pass leaves the one-process last good state; a method other than SPH is refused.
#include <boost/test/unit_test.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <tuple>

#include "core/particle_set.hpp"
#include "io/json_reader.hpp"
#include "parallel/decomposition.hpp"
#include "support/long_run.hpp"
#include "support/pattern.hpp"
#include "support/process.hpp"
#include "sweep.hpp"

using namespace sc;
namespace fs = std::filesystem;

namespace {

const char* mpirun = "/usr/bin/mpirun";
const std::string cases = std::string(SANDCASTLE_SOURCE_DIR) + "/cases";

bool have_mpi() {
  if (sweep_has_mpi() && fs::exists(mpirun)) return true;
  BOOST_TEST_MESSAGE("skipped: built without MPI or no " << mpirun);
  return false;
}

/// `sandcastle args...` as one process (ranks = 1) or under `mpirun -n ranks`, one thread per rank,
/// given `timeout` seconds.
test::ProcessResult sandcastle(int ranks, std::vector<std::string> args, double timeout = 300.0) {
  if (ranks > 1) args.insert(args.begin(), {"--oversubscribe", "-n", std::to_string(ranks), SANDCASTLE_BINARY});
  test::Child child(args,
                    {"OMP_NUM_THREADS=1", "OMPI_ALLOW_RUN_AS_ROOT=1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1",
                     "ASAN_OPTIONS=detect_leaks=0"},
                    ranks > 1 ? mpirun : SANDCASTLE_BINARY);
  test::ProcessResult r = child.wait(timeout);
  BOOST_TEST_INFO(ranks << " ranks: " << r.err);
  BOOST_TEST_REQUIRE(!r.timed_out);
  return r;
}

/// The case `c` written to a fresh folder named after `name`; its path.
std::string written_case(const json& c, const std::string& name) {
  const std::string dir = test::fresh_path(name);
  fs::create_directories(dir);
  std::ofstream(dir + "/case.json") << c.dump();
  return dir + "/case.json";
}

/// The case `name` of cases/ ending at `end` [s] instead (its start-up relaxation and the
/// observer's averaging window shortened to fit), with `patch` merged in (RFC 7386), written to a
/// fresh folder; its path.
std::string shortened_case(const std::string& name, double end, const json& patch = json::object()) {
  json c = read_json_file(cases + "/" + name + "/case.json");
  c.merge_patch(patch);
  c["time"]["end"] = end;
  if (c["time"].value("relax_until", 0.0) >= end) c["time"]["relax_until"] = end / 2;
  if (c["validation"].value("average_time", 0.0) >= end) c["validation"]["average_time"] = end / 3;
  for (auto& [tier, t] : c["tiers"].items()) t.erase("end_time");
  return written_case(c, name);
}

/// Capture group 1 of the first match of `pattern` in `text`; empty when nothing matches.
std::string match(const std::string& text, const std::string& pattern) {
  const auto groups = test::Pattern(pattern).first_in(text);
  return groups ? groups->at(0) : "";
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

/// What `run` printed: the checksum, the decomposition's rebalances, migrated particles and rigid
/// clusters with members on several ranks (summed over the steps), and the particles removed and
/// added at compactions with those next to another rank's slab.
struct Printed {
  std::string checksum;
  long rebalances = -1, migrated = -1, clusters_across = -1, removed = 0, added = 0, at_border = 0;
};
Printed printed(const test::ProcessResult& r) {
  Printed p;
  p.checksum = match(r.out, "checksum ([0-9a-f]{16})");
  const std::string rebalances = match(r.out, "decomposed over \\d+ ranks: (\\d+) rebalances");
  const std::string migrated = match(r.out, "rebalances, (\\d+) particles migrated");
  if (!rebalances.empty()) p.rebalances = std::stol(rebalances);
  if (!migrated.empty()) p.migrated = std::stol(migrated);
  const std::string across = match(r.out, "(\\d+) rigid clusters across ranks");
  if (!across.empty()) p.clusters_across = std::stol(across);
  if (const auto m = test::Pattern("compactions: (\\d+) particles removed, (\\d+) added, (\\d+) of them").first_in(r.out)) {
    p.removed = std::stol(m->at(0));
    p.added = std::stol(m->at(1));
    p.at_border = std::stol(m->at(2));
  }
  return p;
}

/// A checkpoint to write in a run over 3 ranks (at step `every`) and the rank counts to resume it on;
/// none when `every` is 0.
struct Resume {
  int every = 0;
  std::vector<int> on;
};

/// The checkpoint of step `every` in the output folder `dir`, resumed by the case file on each of
/// `resume_on` ranks: every resumed run ends with the checksum `uninterrupted`. Returns what each printed.
std::vector<Printed> resumed_runs(const std::string& case_file, const std::string& dir, const Resume& resume,
                                  const std::string& uninterrupted) {
  char name[32];
  std::snprintf(name, sizeof name, "checkpoint_%08d.ckpt", resume.every);
  const std::string ckpt = dir + "/" + name;
  BOOST_TEST_REQUIRE(fs::exists(ckpt));
  std::vector<Printed> out;
  for (const int ranks : resume.on) {
    const test::ProcessResult resumed = sandcastle(ranks, {"run", case_file, "--out", dir + "_resumed" + std::to_string(ranks), "--resume", ckpt});
    BOOST_TEST_INFO("resumed on " << ranks << ": " << resumed.out);
    out.push_back(printed(resumed));
    BOOST_TEST(out.back().checksum == uninterrupted);
  }
  return out;
}

/// Runs the case file over 1, 2 and 3 ranks and checks that every decomposed run ends in the
/// one-process state: the same checksum and the same final frame (every particle field, in the
/// one-process order), with the same exit code. With a `resume`, the 3-rank run also writes that
/// checkpoint, which resumes on each of its rank counts with the one-process checksum. Returns what
/// each printed (1, 2, 3 ranks, then each resumed run).
std::vector<Printed> runs_agree(const std::string& case_file, const Resume& resume = {}) {
  const std::string root = test::fresh_path("decomposed");
  std::vector<Printed> out;
  std::string frame;
  int code = -1;
  std::size_t runs = 0;  // progress lines ending a run: the case's and its twin's (a dry twin), if any
  for (const int ranks : {1, 2, 3}) {
    const std::string dir = root + "/n" + std::to_string(ranks);
    std::vector<std::string> args{"run", case_file, "--out", dir};
    if (ranks == 3 && resume.every > 0) args.insert(args.end(), {"--checkpoint-every", std::to_string(resume.every)});
    const test::ProcessResult r = sandcastle(ranks, args);
    out.push_back(printed(r));
    BOOST_TEST_INFO(ranks << " ranks: " << r.out << r.err);
    BOOST_TEST_REQUIRE(out.back().checksum.size() == 16u);
    const std::string final_frame = test::read_text(dir + "/final.vtu");
    if (ranks == 1) {
      frame = final_frame;
      code = r.exit_code;
      runs = count(r.err, "  done\n");
      BOOST_TEST(runs >= 1u);
      continue;
    }
    BOOST_TEST(count(r.err, "  done\n") == runs);  // the progress lines are rank 0's alone
    BOOST_TEST(r.exit_code == code);
    BOOST_TEST(out.back().checksum == out.front().checksum);
    BOOST_TEST((final_frame == frame), "final.vtu differs from the one-process run's");
  }
  if (resume.every > 0) {
    const std::vector<Printed> resumed = resumed_runs(case_file, root + "/n3", resume, out.front().checksum);
    out.insert(out.end(), resumed.begin(), resumed.end());
  }
  fs::remove_all(root);
  return out;
}

/// The checkpoint of step `every` written by a run of the case file over 3 ranks, resumed on each
/// of `resume_on` ranks: the 3-rank run and every resumed run end with the checksum of the
/// uninterrupted one-process run. Returns what the 3-rank run and each resumed run printed.
std::vector<Printed> checkpoint_resumes(const std::string& case_file, int every, const std::vector<int>& resume_on = {2}) {
  const std::string root = test::fresh_path("decomposed_restart");
  const test::ProcessResult straight = sandcastle(1, {"run", case_file, "--out", root + "/straight"});
  const test::ProcessResult three = sandcastle(3, {"run", case_file, "--out", root + "/three", "--checkpoint-every", std::to_string(every)});
  std::vector<Printed> out{printed(three)};
  BOOST_TEST(out[0].checksum == printed(straight).checksum);
  const std::vector<Printed> resumed = resumed_runs(case_file, root + "/three", {every, resume_on}, printed(straight).checksum);
  out.insert(out.end(), resumed.begin(), resumed.end());
  fs::remove_all(root);
  return out;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(decomposition)

// The key rule of a compaction, without MPI: a scene of 40 particles dealt to 3 "ranks" in runs of
// keys, random removals and additions (some particles queue two), each rank's keys from every
// rank's notice (compaction_keys). Put at their new keys, the ranks' survivors and additions are
// the one-process ParticleSet::compact, particle for particle (by id: a survivor keeps its id, an
// addition gets the one process's next_id + its place in the queue).
BOOST_AUTO_TEST_CASE(compaction_keys_are_the_one_process_indices_after_compact) {
  std::mt19937 random(7);
  for (int trial = 0; trial < 20; ++trial) {
    const std::size_t n = 40;
    ParticleSet<2> one;
    for (std::size_t i = 0; i < n; ++i) one.append();
    const std::int64_t next_id = one.next_id();  // the first addition's id
    std::vector<int> rank_of(n);
    for (std::size_t i = 0, r = 0; i < n; ++i) {  // runs of keys, as slabs give cells
      if (random() % 6 == 0) r = (r + 1) % 3;
      rank_of[i] = static_cast<int>(r);
    }
    std::vector<CompactionNotice> notice(3);
    std::vector<std::vector<std::uint64_t>> kept(3);
    std::vector<std::vector<std::int64_t>> kept_id(3), added_id(3);
    for (std::size_t i = 0; i < n; ++i) {
      const int r = rank_of[i];
      ++notice[r].particles;
      if (random() % 4 == 0) {
        one.queue_remove(i);
        notice[r].removed.push_back(i);
      } else {
        kept[r].push_back(i);
        kept_id[r].push_back(one.id[i]);
      }
      for (std::uint64_t copies = random() % 5 == 0 ? 1 + random() % 2 : 0; copies > 0; --copies) {
        ParticleSet<2>& add = one.additions();  // queued in storage order, as the porous step queues them
        const std::size_t k = add.append();
        added_id[r].push_back(add.id[k]);
        notice[r].added.push_back({i, notice[r].added.size()});
      }
    }
    one.compact();
    std::vector<std::int64_t> at(one.size(), -1);
    for (int r = 0; r < 3; ++r) {
      const CompactionKeys keys = compaction_keys(kept[r], notice[r].added, notice);
      BOOST_TEST_REQUIRE(keys.survivors + keys.additions == one.size());
      for (std::size_t k = 0; k < kept[r].size(); ++k) at.at(keys.kept[k]) = kept_id[r][k];
      for (std::size_t k = 0; k < keys.added.size(); ++k) {
        at.at(keys.added[k]) = added_id[r][k];
        BOOST_TEST(next_id + static_cast<std::int64_t>(keys.added[k] - keys.survivors) == added_id[r][k]);  // Decomposition::compact's ids
      }
      BOOST_TEST(std::is_sorted(keys.kept.begin(), keys.kept.end()));
      BOOST_TEST(std::is_sorted(keys.added.begin(), keys.added.end()));
    }
    BOOST_TEST(at == one.id, "trial " << trial);
  }
}

// The water column at rest, its start-up (0.3 s, about 2,300 steps with the CFL step): the
// decomposed runs end bitwise where the one process ends.
BOOST_AUTO_TEST_CASE(hydrostatic_over_2_and_3_ranks_is_the_one_process_run, *test::long_run()) {
  if (!have_mpi()) return;
  const std::string file = shortened_case("hydrostatic", 0.3);
  const std::vector<Printed> p = runs_agree(file);
  BOOST_TEST(p[1].rebalances >= 1);
  fs::remove_all(fs::path(file).parent_path());
}

// The collapsing column (0.1 s): particles cross the slabs' borders and the borders move, and the
// decomposed runs still end bitwise where the one process ends.
BOOST_AUTO_TEST_CASE(dam_break_over_2_and_3_ranks_migrates_rebalances_and_is_the_one_process_run) {
  if (!have_mpi()) return;
  const std::string file = shortened_case("dam_break_square", 0.1);
  const std::vector<Printed> p = runs_agree(file);
  for (const std::size_t k : {1u, 2u}) {
    BOOST_TEST_INFO(k + 1 << " ranks");
    BOOST_TEST(p[k].migrated > 0);
    BOOST_TEST(p[k].rebalances > 1);  // the first slabs, then at least one move of a border
  }
  fs::remove_all(fs::path(file).parent_path());
}

// A checkpoint written by 3 ranks resumes on 2 (and on 1) with the checksum of the uninterrupted run.
BOOST_AUTO_TEST_CASE(checkpoint_of_3_ranks_resumes_on_2_with_the_uninterrupted_checksum, *test::long_run()) {
  if (!have_mpi()) return;
  const std::string file = shortened_case("dam_break_square", 0.06);
  checkpoint_resumes(file, 200, {2, 1});
  fs::remove_all(fs::path(file).parent_path());
}

/// Runs the case file, which blows up, in one process and over each of `ranks`: every run stops
/// as the one process does, with exit code 3, the same diagnostic (step, time, the particle's
/// one-process index, its phase, the field) and the same last good state. Returns the diagnostic.
std::string blow_ups_agree(const std::string& file, const std::vector<int>& ranks) {
  const std::string root = test::fresh_path("decomposed_blowup");
  std::string diagnostic, last_good;
  for (const int n : ranks) {
    BOOST_TEST_CONTEXT(n << " ranks") {
      const std::string out = root + "/n" + std::to_string(n);
      const test::ProcessResult r = sandcastle(n, {"run", file, "--out", out});
      BOOST_TEST(r.exit_code == 3);
      const std::string said = match(r.err, "(blow-up at step [^;]*);");
      const std::string frame = test::read_text(out + "/last_good.vtu");
      if (n == 1) {
        diagnostic = said;
        last_good = frame;
      }
      BOOST_TEST(said == diagnostic);
      BOOST_TEST((frame == last_good), "last_good.vtu differs from the one-process run's");
    }
  }
  BOOST_TEST(!diagnostic.empty());
  fs::remove_all(root);
  return diagnostic;
}

// A run that blows up over 2 ranks stops as the one process does.
BOOST_AUTO_TEST_CASE(a_blow_up_over_2_ranks_is_reported_as_in_one_process) {
  if (!have_mpi()) return;
  blow_ups_agree(std::string(SANDCASTLE_SOURCE_DIR) + "/tests/reliability/unstable_step.json", {1, 2});
}

/// The step number in a blow-up diagnostic.
long blow_up_step(const std::string& diagnostic) {
  const std::string step = match(diagnostic, "blow-up at step (\\d+),");
  BOOST_TEST_REQUIRE(!step.empty());
  return std::stol(step);
}

// A blow-up in a step that began with a storage sort (Simulator::kSortEvery): darcy_column with the
// domain's floor just below the bed's seepage face (no tank floor), so that water emitted there
// leaves the domain. Over 2 and 3 ranks the last good state is the one process's, in its order:
// both sort before the blow-up guard keeps the state. The floor's height sets the step at which the
// first water leaves and is chosen so that this step sorts; a change of the physics can move it off
// a sorting step, which the test reports (re-choose the height then).
BOOST_AUTO_TEST_CASE(a_blow_up_in_a_sort_step_over_2_and_3_ranks_is_reported_as_in_one_process, *test::long_run()) {
  if (!have_mpi()) return;
  const json cut_below_the_bed = {{"domain", {{"min", {-0.1, 0.199}}}},
                                  {"tank", {{"min", {0.0, 0.199}}, {"sides", {{"y-", "open"}}}}}};
  const std::string file = shortened_case("darcy_column", 0.5, cut_below_the_bed);
  const std::string diagnostic = blow_ups_agree(file, {1, 2, 3});
  BOOST_TEST((blow_up_step(diagnostic) - 1) % 16 == 0, diagnostic << ": not a step that sorts");
  fs::remove_all(fs::path(file).parent_path());
}

// A blow-up in a step with an adaptivity pass: the small adaptive dam break with a pass every step
// and a fixed step far beyond its stability limit. The pass merges and splits (new keys on every
// rank); over 2 and 3 ranks the last good state, from before the pass, is the one process's: each
// rank gathers it by the keys it had then.
BOOST_AUTO_TEST_CASE(a_blow_up_in_a_step_with_an_adaptivity_pass_over_2_and_3_ranks_is_reported_as_in_one_process) {
  if (!have_mpi()) return;
  json c = read_json_file(std::string(SANDCASTLE_SOURCE_DIR) + "/tests/reliability/small_dam_break_adaptive.json");
  c.merge_patch({{"time", {{"dt", 0.02}, {"cfl", 0.0}, {"frame_interval", 0.0}}}, {"adaptive", {{"interval", 1}}}});
  const std::string file = written_case(c, "adaptive_blowup");
  BOOST_TEST(blow_up_step(blow_ups_agree(file, {1, 2, 3})) >= 2);  // the passes begin with the second step
  fs::remove_all(fs::path(file).parent_path());
}

// A step that the CFL condition collapses (Simulator::runaway, core/errors.hpp kShortestStepFraction):
// the small dam break's block in free fall under 1e9 m/s^2, without a tank, until its speed of
// about 4e4 m/s shrinks the step below 1e-4 of the case's 1 ms (after some 200 steps, storage sorts
// among them). The ranks agree on the step size, so every rank takes the check's rare branch in the
// same step; over 2 and 3 ranks the diagnostic (the particle, its one-process index, and its speed)
// and the last good state are the one process's.
BOOST_AUTO_TEST_CASE(a_collapsed_step_over_2_and_3_ranks_is_reported_as_in_one_process) {
  if (!have_mpi()) return;
  json c = read_json_file(std::string(SANDCASTLE_SOURCE_DIR) + "/tests/reliability/small_dam_break.json");
  c.erase("tank");
  c.merge_patch({{"gravity", {0.0, -1e9}}, {"domain", {{"min", {-0.1, -10.0}}}}});
  c["validation"] = {{"observer", "scene"}};
  const std::string file = written_case(c, "collapsed_step");
  const std::string diagnostic = blow_ups_agree(file, {1, 2, 3});
  BOOST_TEST(diagnostic.find("field 'velocity': a speed of") != std::string::npos, diagnostic);
  BOOST_TEST(blow_up_step(diagnostic) > 16);  // past the first storage sort
  fs::remove_all(fs::path(file).parent_path());
}

// A file rank 0 cannot write, at the start (the output folder) or in the middle of the run (the
// second frame, where a folder of that name stands), ends every rank promptly, not only rank 0:
// exit code 4 as in one process, the error told once, naming the rank and the file.
BOOST_AUTO_TEST_CASE(a_file_rank_0_cannot_write_ends_every_rank_with_the_error) {
  if (!have_mpi()) return;
  const std::string file = shortened_case("dam_break_square", 0.03);
  const std::string out = test::fresh_path("decomposed_unwritable");
  fs::create_directories(out + "/frame_00001.vtu");
  for (const std::string& dir : {std::string("/dev/null/out"), out}) {
    BOOST_TEST_INFO("--out " << dir);
    const test::ProcessResult r = sandcastle(2, {"run", file, "--out", dir}, 60.0);
    BOOST_TEST(r.exit_code == 4);
    BOOST_TEST(count(r.err, "error: rank 0: ") == 1u);
    BOOST_TEST(r.err.find(dir == out ? "frame_00001.vtu" : "/dev/null/out") != std::string::npos);
  }
  BOOST_TEST(fs::exists(out + "/frame_00000.vtu"));
  BOOST_TEST(!fs::exists(out + "/final.vtu"));
  fs::remove_all(out);
  fs::remove_all(fs::path(file).parent_path());
}

// `bench` of a decomposed scene: rank 0 writes bench.json with the one-process checksum, the ranks,
// the halo stage and its share of the step.
BOOST_AUTO_TEST_CASE(bench_over_2_ranks_reports_the_halo_share_and_the_one_process_checksum) {
  if (!have_mpi()) return;
  const std::string root = test::fresh_path("decomposed_bench");
  fs::create_directories(root);
  const std::string limits = root + "/probe.json";  // the roofline's limits at the runs' one thread, given rather than measured
  std::ofstream(limits) << R"({"rows": [{"threads": 1, "bandwidth_bytes_per_s": 2e10, "flops_per_s": 1e10}]})";
  std::vector<json> entries;
  for (const int ranks : {1, 2}) {
    const std::string out = root + "/n" + std::to_string(ranks);
    const test::ProcessResult r =
        sandcastle(ranks, {"bench", "--scene", "dam_break_square", "--steps", "20", "--limits", limits, "--out", out});
    BOOST_TEST_REQUIRE(r.exit_code == 0);
    entries.push_back(read_json_file(out + "/bench.json").at("scenes").at(0));
  }
  BOOST_TEST(entries[1]["checksum"] == entries[0]["checksum"]);
  BOOST_TEST(entries[1]["ranks"] == 2);
  BOOST_TEST(!entries[0].contains("ranks"));
  BOOST_TEST(entries[0]["roofline"]["limits"]["bandwidth_bytes_per_s"].get<double>() == 2e10);  // one process only
  BOOST_TEST(!entries[1].contains("roofline"));
  const double share = entries[1]["halo_share"];
  BOOST_TEST((share > 0.0 && share < 1.0));
  BOOST_TEST(entries[1]["stage_ms_per_step"]["halo"].get<double>() > 0.0);
  fs::remove_all(root);
}

// Porous flow through a fixed bed (Lenaerts 2008, solver/porous/), shortened: water is absorbed
// at the pond (all three) and emitted at the seepage face (darcy_column) while particles migrate,
// and the decomposed runs end bitwise where the one process ends. Over 3 ranks the slabs' borders
// lie at the pond and the seepage face, and particles that another rank holds a halo copy of are
// removed or emit there (the compaction keys, the scene-wide water columns and pore-pressure solve,
// the gathered absorptions and placements at work at a border).
BOOST_AUTO_TEST_CASE(porous_beds_over_2_and_3_ranks_are_the_one_process_run, *test::long_run()) {
  if (!have_mpi()) return;
  for (const auto& [name, end] : std::vector<std::pair<std::string, double>>{{"darcy_column", 0.5}, {"green_ampt", 0.15}, {"capillary_rise", 0.15}}) {
    BOOST_TEST_CONTEXT(name) {
      const std::string file = shortened_case(name, end);
      const std::vector<Printed> p = runs_agree(file);
      BOOST_TEST(p[1].removed + p[1].added > 0);
      BOOST_TEST(p[2].removed + p[2].added > 0);
      BOOST_TEST(p[2].at_border > 0);
      if (name == "darcy_column") BOOST_TEST(p[2].added > 0);
      fs::remove_all(fs::path(file).parent_path());
    }
  }
}

// A porous run's checkpoint written by 3 ranks, after water was absorbed, resumes on 2 with the
// uninterrupted checksum while absorption goes on.
BOOST_AUTO_TEST_CASE(porous_checkpoint_of_3_ranks_resumes_on_2_with_the_uninterrupted_checksum) {
  if (!have_mpi()) return;
  const std::string file = shortened_case("green_ampt", 0.15);
  BOOST_TEST(checkpoint_resumes(file, 300)[0].removed > 0);
  fs::remove_all(fs::path(file).parent_path());
}

// Sand over ranks (sand/clusters_over_ranks.hpp): the sand case `name`, shortened to end at `end`
// [s], ends bitwise in the one-process state at 2 and 3 ranks, while at 2 ranks sand particles
// migrate and rigid clusters have members on both ranks (their sums gathered in the one-process order).
void sand_runs_agree(const std::string& name, double end, const json& patch = json::object(), const Resume& resume = {}) {
  const std::string file = shortened_case(name, end, patch);
  const std::vector<Printed> p = runs_agree(file, resume);
  BOOST_TEST(p[1].migrated > 0);
  BOOST_TEST(p[1].clusters_across > 0);
  fs::remove_all(fs::path(file).parent_path());
}

// The granular column collapsing over the floor: frictional stress and wall friction across the cut.
// Its checkpoint written by 3 ranks at step 400 resumes on 2 with the uninterrupted checksum.
BOOST_AUTO_TEST_CASE(column_collapse_over_2_and_3_ranks_is_the_one_process_run_and_resumes_on_2, *test::long_run()) {
  if (!have_mpi()) return;
  sand_runs_agree("column_collapse", 0.2, json::object(), {400, {2}});
}

// The pile spreading to its angle of repose.
BOOST_AUTO_TEST_CASE(angle_of_repose_over_2_and_3_ranks_is_the_one_process_run, *test::long_run()) {
  if (!have_mpi()) return;
  sand_runs_agree("angle_of_repose", 0.2);
}

// A cohesive block falling freely as one rigid cluster cut by the slabs.
BOOST_AUTO_TEST_CASE(rigid_cluster_over_2_and_3_ranks_is_the_one_process_run) {
  if (!have_mpi()) return;
  sand_runs_agree("rigid_cluster", 0.1);
}

// The same block landing on a no-slip floor: the floor's contact impulses on a cluster cut by the
// slabs (resolve_wall_contacts) swept in the one-process contact order.
BOOST_AUTO_TEST_CASE(rigid_cluster_landing_on_a_floor_over_2_and_3_ranks_is_the_one_process_run, *test::long_run()) {
  if (!have_mpi()) return;
  const json floor = {{"tank", {{"min", {-0.15, -0.03}}, {"max", {0.15, 0.2}},
                                {"sides", {{"x-", "slip"}, {"x+", "slip"}, {"y-", "no_slip"}, {"y+", "open"}}}}}};
  sand_runs_agree("rigid_cluster", 0.15, floor);
}

// Three spinning rigid blocks in 3-D: the middle one turns across the cut of 2 ranks (at 3 ranks the
// cuts fall between the blocks).
BOOST_AUTO_TEST_CASE(rigid_spin_3d_over_2_and_3_ranks_is_the_one_process_run, *test::long_run()) {
  if (!have_mpi()) return;
  sand_runs_agree("rigid_spin_3d", 0.2);
}

// Adaptive sampling (solver/adaptive/), shortened: the dam break whose deep water merges while its
// front runs over the floor, and the forced cycles of split_merge (everything merged, then split
// back). Every pass runs on the gathered scene on every rank; over 2 and 3 ranks the runs end
// bitwise in the one-process state, with particles split or merged next to a slab's border.
BOOST_AUTO_TEST_CASE(adaptive_runs_over_2_and_3_ranks_are_the_one_process_run, *test::long_run()) {
  if (!have_mpi()) return;
  // Without the uniform twins (one-process runs of their own) and the metrics comparing with them.
  const json no_twin = {{"validation", {{"uniform_twin", nullptr},
                                        {"metrics", {{"front_vs_uniform_rms", nullptr}, {"pressure_l2_vs_uniform_ratio", nullptr}}}}}};
  for (const auto& [name, end] : std::vector<std::pair<std::string, double>>{{"dam_break_adaptive", 0.1}, {"split_merge", 0.25}}) {
    BOOST_TEST_CONTEXT(name) {
      const std::string file = shortened_case(name, end, no_twin);
      const std::vector<Printed> p = runs_agree(file);
      for (const int ranks : {2, 3}) {
        BOOST_TEST(p[ranks - 1].removed > 0);
        BOOST_TEST(p[ranks - 1].added > 0);
        BOOST_TEST(p[ranks - 1].at_border > 0);
      }
      fs::remove_all(fs::path(file).parent_path());
    }
  }
}

// Wet sand over ranks: the poured water of wet_sand_collapse is absorbed by the moving column of
// porous sand (Darcy flow and capillarity between moving particles, pore pressure, wet cohesion,
// the held water in the sand's mass and in its rigid clusters) while the slabs cut the column, and
// the water in the duck of thesis_duck (coarsened to keep the test short) likewise. The decomposed
// runs end bitwise where the one process ends, with water particles absorbed next to a slab's
// border (by particles another rank holds a halo copy of). The column's checkpoint written by 3
// ranks at step 600, after the sand absorbed water, resumes on 2 with the uninterrupted checksum
// while the absorption goes on.
BOOST_AUTO_TEST_CASE(wet_sand_over_2_and_3_ranks_is_the_one_process_run_and_resumes_on_2, *test::long_run()) {
  if (!have_mpi()) return;
  json duck = read_json_file(cases + "/thesis_duck/case.json")["meshes"];
  duck[0]["file"] = cases + "/meshes/duck.obj";  // the shortened case lies in another folder
  const json coarse = {{"meshes", duck}, {"tiers", {{"quick", {{"spacings", {0.02}}}}}}};
  for (const auto& [name, end, patch, resume] : std::vector<std::tuple<std::string, double, json, Resume>>{
           {"wet_sand_collapse", 0.2, json::object(), {600, {2}}}, {"thesis_duck", 0.3, coarse, {}}}) {
    BOOST_TEST_CONTEXT(name) {
      const std::string file = shortened_case(name, end, patch);
      const std::vector<Printed> p = runs_agree(file, resume);
      BOOST_TEST(p[1].migrated > 0);
      BOOST_TEST(p[1].removed > 0);
      BOOST_TEST(p[2].removed > 0);
      BOOST_TEST(p[2].at_border > 0);
      if (resume.every > 0) BOOST_TEST(p[3].removed > 0);  // the absorption goes on after the resume
      fs::remove_all(fs::path(file).parent_path());
    }
  }
}

// An adaptive run's checkpoint written by 3 ranks between passes resumes on 2 with the
// uninterrupted checksum while the passes go on.
BOOST_AUTO_TEST_CASE(adaptive_checkpoint_of_3_ranks_resumes_on_2_with_the_uninterrupted_checksum) {
  if (!have_mpi()) return;
  const json no_twin = {{"validation", {{"uniform_twin", nullptr}, {"metrics", {{"front_vs_uniform_rms", nullptr}}}}}};
  const std::string file = shortened_case("dam_break_adaptive", 0.1, no_twin);
  BOOST_TEST(checkpoint_resumes(file, 50)[1].removed > 0);  // passes go on after the resume
  fs::remove_all(fs::path(file).parent_path());
}

// Wet sand with adaptive sampling (sand_water_adaptive_3d, shortened past its first pass): the water
// splits and merges beside moving porous sand that absorbs it, every decomposed feature at once.
BOOST_AUTO_TEST_CASE(adaptive_wet_sand_over_2_and_3_ranks_is_the_one_process_run, *test::long_run()) {
  if (!have_mpi()) return;
  const std::string file = shortened_case("sand_water_adaptive_3d", 0.03);
  const std::vector<Printed> p = runs_agree(file);
  BOOST_TEST(p[1].removed + p[1].added > 0);
  BOOST_TEST(p[2].removed + p[2].added > 0);
  fs::remove_all(fs::path(file).parent_path());
}

// A method other than SPH is not decomposed: over 2 ranks the run stops before it starts, with exit
// code 2 and a message naming the case file, the JSON path and the rule; nothing is written.
BOOST_AUTO_TEST_CASE(a_case_of_another_method_over_2_ranks_stops_with_exit_code_2) {
  if (!have_mpi()) return;
  const std::string out = test::fresh_path("decomposed_mpm");
  const test::ProcessResult r = sandcastle(2, {"run", cases + "/column_collapse/case.json", "--method", "mpm", "--out", out});
  BOOST_TEST(r.exit_code == 2);
  BOOST_TEST(r.err.find("column_collapse/case.json") != std::string::npos);
  BOOST_TEST(r.err.find("/method") != std::string::npos);
  BOOST_TEST(r.err.find("not decomposed") != std::string::npos);
  BOOST_TEST(!fs::exists(out));
}

BOOST_AUTO_TEST_SUITE_END()
