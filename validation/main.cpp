// The `sandcastle` command: run one case, validate the suite, render a run's frames. Exit codes: 0
// success, 1 a case failed its gate, 2 bad input (file, JSON path and rule on stderr), 3 the
// simulation blew up, 4 an unexpected internal error, 5 a program `render` needs is missing or
// failed. Over MPI ranks, an error on one rank of a scene is told once, naming the rank.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>

#include "baseline.hpp"
#include "compare.hpp"
#include "core/errors.hpp"
#include "data_root.hpp"
#include "io/atomic_file.hpp"
#include "method/registry.hpp"
#include "bench.hpp"
#include "parallel/comm.hpp"
#include "render/render.hpp"
#include "report.hpp"
#include "runner.hpp"
#include "sweep.hpp"
#include "scene/scene_builder.hpp"

namespace {

/// An output folder: absent (it will be created) or an existing folder, not a file.
const CLI::Validator output_folder(
    [](std::string& path) {
      return std::filesystem::exists(path) && !std::filesystem::is_directory(path)
                 ? "output folder " + path + " exists and is not a folder" : std::string();
    },
    "FOLDER");

int run_command(const std::string& case_file, const std::string& out_dir, const std::string& tier, double spacing,
                long checkpoint_every, const std::string& resume_from, const std::string& method, double max_particles,
                bool surfaces) {
  const sc::CaseSpec spec = sc::with_method(sc::load_case(case_file), method);
  if (surfaces && spec.dimension != 3)
    throw sc::InputError(case_file, "/dimension", "--surface needs a 3-D case (2-D cases are drawn as particles)");
  if (!spec.tiers.count(tier)) throw sc::InputError(case_file, "/tiers", "the case has no " + tier + " tier (try --tier full)");
  const double dx = spacing > 0.0 ? spacing : spec.tiers.at(tier).spacings.back();
  sc::check_particle_count(spec, dx, max_particles, spacing > 0.0 ? "(--spacing)" : "/tiers/" + tier + "/spacings");
  sc::RunSettings settings;
  settings.out_dir = out_dir;
  settings.write_frames = true;
  settings.write_surfaces = surfaces;
  settings.end_time = spacing > 0.0 ? 0.0 : spec.tiers.at(tier).end_time;
  settings.label = spec.name;
  settings.checkpoint_every = checkpoint_every;
  settings.resume_from = resume_from;
  settings.decompose = sc::sweep_ranks() > 1;
  const sc::RunResult r = sc::run_simulation(spec, dx, settings);
  const sc::Comm ranks = settings.decompose ? sc::Comm::world() : sc::Comm();
  if (r.status != "error")  // every rank has the same status
    sc::run_agreed(ranks, [&] {
      if (ranks.rank() == 0) sc::write_series_file(out_dir + "/series.json", spec.name, r.observed);
    });
  if (ranks.rank() != 0) return r.exit_code;  // rank 0 reports
  if (r.status == "error") {
    std::cerr << "error: " << r.message << "\n";
    return r.exit_code;
  }
  std::cout << spec.name << ": " << r.particles << " particles, " << r.steps << " steps, " << r.wall_seconds
            << " s, checksum " << r.checksum << "\n";
  if (const auto& a = r.decomposition)
    std::cout << "  decomposed over " << a->ranks << " ranks: " << a->rebalances << " rebalances, " << a->migrated
              << " particles migrated, " << a->halo_particles << " halo particles received over " << a->steps << " steps, " << a->clusters_across_ranks
              << " rigid clusters across ranks\n";
  if (const auto& a = r.decomposition; a && a->removed + a->added > 0)
    std::cout << "  compactions: " << a->removed << " particles removed, " << a->added << " added, " << a->at_border
              << " of them by a particle next to another rank's slab\n";
  for (const auto& [name, m] : r.observed.metrics)
    std::cout << "  " << name << " = " << m.value << "  limit " << m.limit.to_json().dump() << (m.pass() ? "" : "  FAIL")
              << "\n";
  std::cout << "frames: " << out_dir << "/frames.pvd (open in ParaView)\n";
  return r.exit_code;
}

/// `sandcastle baseline`: runs the cases (unless --from names a finished run), then writes their
/// baselines. A case that failed to run gets no baseline and makes the exit code non-zero.
int bless_command(const sc::ValidateOptions& options, const std::string& from) {
  const int run_code = from.empty() ? sc::validate(options) : sc::kSuccess;
  const int bless_code = sc::write_baselines(from.empty() ? options.out_dir : from, sc::baselines_folder(options),
                                             options.cases, options.methods);
  return run_code == sc::kBadInput || run_code == sc::kBlowUp ? run_code : bless_code;
}

/// --method of validate and baseline: a comma-separated list of known methods, or "all".
void add_methods_option(CLI::App* app, std::vector<std::string>& methods) {
  std::vector<std::string> allowed = sc::method_names();
  allowed.push_back("all");
  app->add_option("--method", methods,
                  "run each case with these methods (comma-separated), each one it supports; \"all\": every "
                  "method it supports (default: the case's own \"method\")")
      ->delimiter(',')
      ->check(CLI::IsMember(allowed));
}

}  // namespace

/// The exit code of an error on one rank of a scene over ranks: the one its kind gives in one process.
int exit_code_of(sc::RankError::Kind kind) {
  switch (kind) {
    case sc::RankError::Kind::Input: return sc::kBadInput;
    case sc::RankError::Kind::BlowUp: return sc::kBlowUp;
    case sc::RankError::Kind::Other: return sc::kInternalError;
  }
  return sc::kInternalError;
}

/// `validate` spreads its cases over MPI ranks, `run` and `bench` decompose one scene over them; any
/// other command under `mpirun -n N` (N > 1) would run N copies writing the same files, so it stops
/// before anything is written. True when stopped.
bool sweep_ranks_guard(bool over_ranks) {
  if (over_ranks || sc::sweep_ranks() == 1) return false;
  if (sc::sweep_rank() == 0)
    std::cerr << "error: only `sandcastle validate`, `run` and `bench` run over several MPI ranks (this is rank 0 of "
              << sc::sweep_ranks() << "); run the other commands as one process\n";
  return true;
}

int main(int argc, char** argv) {
  const sc::MpiSession mpi(argc, argv);  // MPI only under mpirun (validation/sweep.hpp)
  CLI::App app{"sandcastle: particle-based sand + water simulation and its validation suite"};
  app.require_subcommand(1);
  app.fallthrough();  // --root may follow the subcommand
  std::string root;
  app.add_option("--root", root,
                 "folder holding cases/, reference/ and reports/ (default: $SANDCASTLE_ROOT, else the source tree)");
  double max_particles = sc::kDefaultMaxParticles;
  const std::string max_help = "stop with exit 2 before a run whose estimated particle count exceeds this";

  std::string case_file, run_out, run_tier = "quick";
  double spacing = 0.0;
  CLI::App* run = app.add_subcommand("run", "Simulate one case, writing VTU frames (ParaView) and series");
  run->add_option("case", case_file, "case file (cases/<name>/case.json)")->required()->check(CLI::ExistingFile);
  run->add_option("--out", run_out, "output folder")->required()->check(output_folder);
  run->add_option("--tier", run_tier, "tier whose finest spacing is used")->check(CLI::IsMember({"quick", "full"}));
  run->add_option("--spacing", spacing, "particle spacing [m], overriding the tier")->check(CLI::PositiveNumber);
  long checkpoint_every = 0;
  std::string resume_from;
  run->add_option("--checkpoint-every", checkpoint_every, "write DIR/checkpoint_<step>.ckpt every N steps")
      ->check(CLI::PositiveNumber);
  run->add_option("--resume", resume_from, "continue from this checkpoint (same case and spacing)")
      ->check(CLI::ExistingFile);
  run->add_option("--max-particles", max_particles, max_help)->check(CLI::PositiveNumber);
  std::string run_method;
  run->add_option("--method", run_method, "simulation method, overriding the case's \"method\" (one the case supports)");
  bool run_surfaces = false;
  run->add_flag("--surface", run_surfaces,
                "with each frame, write surface_<phase>_NNNNN.vtp of the water and the sand (3-D; listed in frames.pvd)");

  sc::ValidateOptions vopt;
  CLI::App* val = app.add_subcommand("validate", "Run the validation cases and write report.json, plots, summary.md");
  val->add_option("--tier", vopt.tier, "quick (CI) or full (users)")->check(CLI::IsMember({"quick", "full"}));
  val->add_option("--case", vopt.cases, "run only these cases (repeatable)");
  val->add_option("--out", vopt.out_dir, "output folder")->required()->check(output_folder);
  val->add_option("--cases-dir", vopt.cases_dir, "folder of cases (default: the repository's cases/)");
  val->add_flag("!--no-plots", vopt.plots, "skip the PNG plots, the filmstrips and report.html");
  val->add_flag("!--no-pictures", vopt.pictures,
                "skip the filmstrips (each case's finest run drawn at its first, middle and last frame, or at the "
                "frames of its render.filmstrip; docs/render.md)");
  val->add_option("--baselines-dir", vopt.baselines_dir, "folder of baselines (default: reference/baselines)");
  val->add_option("--max-particles", vopt.max_particles, max_help)->check(CLI::PositiveNumber);
  val->add_flag("--errata", vopt.errata,
                "also run each erratum's printed form on the cases it affects (errata-impact table)");
  val->add_flag("--convergence", vopt.convergence,
                "instead of a tier, run the cases' convergence studies (\"convergence\" in the case file): "
                "errors and observed orders against the spacing, log-log plots")
      ->excludes(val->get_option("--errata"));
  add_methods_option(val, vopt.methods);

  sc::ValidateOptions bopt;
  bopt.plots = false;
  bopt.pictures = false;
  std::string bless_from;
  CLI::App* bl = app.add_subcommand("baseline",
                                    "Bless baselines: write reference/baselines/<case>.json (<case>.<method>.json for "
                                    "a method other than the case's own) from a run");
  bl->add_option("--tier", bopt.tier, "quick or full")->check(CLI::IsMember({"quick", "full"}));
  bl->add_option("--case", bopt.cases, "only these cases (repeatable)");
  bl->add_option("--out", bopt.out_dir, "folder of the run (default: reports/baseline-run under the root)");
  bl->add_option("--cases-dir", bopt.cases_dir, "folder of cases (default: the repository's cases/)");
  bl->add_option("--baselines-dir", bopt.baselines_dir, "folder of baselines (default: reference/baselines)");
  bl->add_option("--from", bless_from, "bless this finished validation run instead of running the cases")
      ->check(CLI::ExistingDirectory);
  add_methods_option(bl, bopt.methods);

  std::string compare_a, compare_b, compare_out;
  bool compare_plots = true;
  CLI::App* cmp = app.add_subcommand("compare", "Diff two validation runs: compare.json, compare.md, compare.html");
  cmp->add_option("run_a", compare_a, "first run folder (with report.json)")->required()->check(CLI::ExistingDirectory);
  cmp->add_option("run_b", compare_b, "second run folder")->required()->check(CLI::ExistingDirectory);
  cmp->add_option("--out", compare_out, "output folder")->required();
  cmp->add_flag("!--no-plots", compare_plots, "skip the overlay plots and compare.html");

  sc::BenchOptions benchopt;
  CLI::App* bench = app.add_subcommand("bench", "Time scenes per step and compare with the thesis: DIR/bench.json");
  bench->add_option("--scene", benchopt.scenes, "scene (case name) to time, repeatable (default: thesis + water scenes)");
  bench->add_option("--steps", benchopt.steps, "steps per scene (default 200 water benchmarks, 100 others)")
      ->check(CLI::PositiveNumber);
  bench->add_option("--threads", benchopt.threads, "OpenMP threads (default: OMP_NUM_THREADS)")->check(CLI::PositiveNumber);
  bench->add_option("--out", benchopt.out_dir, "output folder")->required()->check(output_folder);
  bench->add_option("--cases-dir", benchopt.cases_dir, "folder of cases (default: the repository's cases/)");
  bench->add_option("--method", benchopt.method, "simulation method, overriding each scene's \"method\" (one the scene supports)");
  bench->add_option("--max-particles", benchopt.max_particles, max_help)->check(CLI::PositiveNumber);
  bench->add_flag("--probe", benchopt.probe,
                  "instead of scenes, measure memory bandwidth (STREAM triad) and double-precision throughput at "
                  "1 .. --threads threads: DIR/probe.json")
      ->excludes("--scene");
  bench->add_option("--limits", benchopt.limits,
                    "probe.json (bench --probe) to read the roofline's limits from, at this run's thread count "
                    "(default: measure them first, a few seconds)")
      ->check(CLI::ExistingFile);
  bench->add_flag("--surface", benchopt.surface,
                  "instead of scenes, time the surface reconstruction of a 68,921-particle block at a quarter of the "
                  "spacing and on a 250^3 grid: DIR/surface.json")
      ->excludes("--scene")
      ->excludes("--probe");

  sc::render::RenderOptions ropt;
  CLI::App* rnd = app.add_subcommand("render", "Pictures of a run's frames (POV-Ray surfaces, 2-D particle snapshots), "
                                               "a filmstrip and a video (docs/render.md)");
  rnd->add_option("run_dir", ropt.run_dir, "folder of a `sandcastle run` (with frames.pvd)")
      ->required()
      ->check(CLI::ExistingDirectory);
  rnd->add_option("--out", ropt.out_dir, "output folder")->required()->check(output_folder);
  rnd->add_option("--case", ropt.case_file, "the run's case file (default: the case named in RUN_DIR/series.json)")
      ->check(CLI::ExistingFile);
  rnd->add_option("--filmstrip", ropt.frames,
                  "write DIR/filmstrip.png of these frames side by side (comma-separated; none given: the case's "
                  "render.filmstrip, else first, middle, last)")
      ->expected(0, -1)
      ->delimiter(',')
      ->check(CLI::NonNegativeNumber);
  rnd->add_flag("--video", ropt.video, "write DIR/video.mp4 of every frame (ffmpeg, H.264)");
  rnd->add_flag("--only-filmstrip", ropt.strip_only, "draw only the filmstrip's frames (implies --filmstrip)")
      ->excludes("--video");
  rnd->add_option("--jobs", ropt.jobs, "frames rendered at a time (default 2)")->check(CLI::PositiveNumber);

  try {
    app.parse(argc, argv);
    const CLI::Option* filmstrip = rnd->get_option("--filmstrip");
    ropt.filmstrip = filmstrip->count() > 0 || ropt.strip_only;
    if (filmstrip->results() == std::vector<std::string>{""}) ropt.frames.clear();  // a bare --filmstrip: CLI11 reads "" as 0
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : sc::kBadInput;
  }
  bool one_scene_over_ranks = false;  // `run` or `bench` decomposing a scene over the ranks
  try {
    sc::set_data_root(root);
    if (bopt.out_dir.empty()) bopt.out_dir = sc::data_path("reports/baseline-run");
    one_scene_over_ranks = sc::sweep_ranks() > 1 && (run->parsed() || (bench->parsed() && !benchopt.probe && !benchopt.surface));
    if (sweep_ranks_guard(val->parsed() || one_scene_over_ranks)) return sc::kBadInput;
    if (*run)
      return run_command(case_file, run_out, run_tier, spacing, checkpoint_every, resume_from, run_method, max_particles,
                         run_surfaces);
    if (*bl) return bless_command(bopt, bless_from);
    if (*cmp) return sc::compare_runs(compare_a, compare_b, compare_out, compare_plots);
    if (*bench) return sc::bench(benchopt);
    if (*rnd) return sc::render::render_run(ropt);
    return sc::validate(vopt);
  } catch (const sc::RankError& e) {  // known to every rank of one scene: rank 0 tells
    if (sc::sweep_rank() == 0) std::cerr << "error: " << e.what() << "\n";
    return exit_code_of(e.kind());
  } catch (const sc::InputError& e) {
    if (val->parsed() || sc::sweep_rank() == 0) std::cerr << "error: " << e.what() << "\n";  // one scene: every rank says the same
    return sc::kBadInput;
  } catch (const std::exception& e) {
    if (!one_scene_over_ranks) {
      std::cerr << "error: " << e.what() << "\n";
      return sc::kInternalError;
    }
    // On this rank only, perhaps between two exchanges the other ranks wait in: the last resort.
    std::cerr << "error: rank " << sc::sweep_rank() << " of " << sc::sweep_ranks() << ": " << e.what()
              << "; ending every rank\n";
    sc::Comm::world().abort(sc::kInternalError);
  }
}
