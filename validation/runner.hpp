// Runs cases: a single simulation (`sandcastle run`) or the validation suite (`sandcastle
// validate`), writing frames, series, report.json, plots and summary.md.
#pragma once
#include <string>
#include <vector>

#include "case/case_file.hpp"
#include "parallel/decomposition.hpp"
#include "scene/scene_builder.hpp"
#include "observer.hpp"

namespace sc {

/// Exit codes of the command (docs/architecture.md "Contracts"); kToolMissing: a program `render`
/// runs (povray, ffmpeg, python3-matplotlib) is missing or failed.
enum ExitCode { kSuccess = 0, kCaseFailed = 1, kBadInput = 2, kBlowUp = 3, kInternalError = 4, kToolMissing = 5 };

/// One simulation of a case at one spacing.
struct RunResult {
  double spacing = 0.0;
  std::string status = "pass";  ///< pass | fail | error
  std::string message;          ///< diagnostic when status is error
  int exit_code = kSuccess;
  double wall_seconds = 0.0;
  std::size_t particles = 0;
  long steps = 0;
  std::string checksum;
  ObserverResult observed;
  /// Moving (water and sand) particles after every step, and the mean over the run: what
  /// adaptivity saves (validation/adaptive_report.hpp).
  Series moving_particles{"moving_particles", "time [s]", "moving particles", {}, {}};
  double moving_particles_mean = 0.0;
  std::optional<AdaptAccount> adapt;  ///< what split and merge did (adaptive cases)
  std::optional<DecompositionAccount> decomposition;  ///< what the decomposition over MPI ranks did (RunSettings::decompose)
};

struct RunSettings {
  std::string out_dir;          ///< where this run writes its files
  double end_time = 0.0;        ///< 0 = the case's end time
  bool write_frames = false;    ///< VTU frames at the case's frame interval (`run`)
  bool write_surfaces = false;  ///< with each frame, the surface of each phase (3-D, `run --surface`)
  std::string label;            ///< progress label
  long checkpoint_every = 0;    ///< write checkpoint_<step>.ckpt every N steps (0: none)
  std::string resume_from;      ///< checkpoint to continue from (empty: start at t = 0)
  /// The scene decomposed over the MPI ranks of the run (`mpirun -n N sandcastle run`): every rank
  /// runs this with the same settings; rank 0 alone writes the files, the same ones a single
  /// process writes.
  bool decompose = false;
};

/// One simulation of `spec` at spacing dx by its method, with its observer: no twin runs. Never
/// throws for a blow-up (status error, exit code 3, last good state written to
/// out_dir/last_good.vtu and last_good.ckpt); throws InputError for bad input (before anything is
/// written).
RunResult run_single(const CaseSpec& spec, double dx, const RunSettings& settings);

/// What a case asks of a run: run_single, then the comparisons with the twin runs its validation
/// block requests (the adaptive run's "uniform_twin", validation/adaptive_report.hpp; the
/// "dry_twin", validation/dry_twin_report.hpp). Each twin is itself a run_single, so a twin never
/// starts twins of its own. Errors as run_single.
RunResult run_simulation(const CaseSpec& spec, double dx, const RunSettings& settings);

/// The surface file of frame k of phase p that `run --surface` writes: surface_<phase>_NNNNN.vtp.
std::string surface_file_name(Phase phase, std::size_t frame);

/// Writes series.json for a case (its series and plot descriptions).
void write_series_file(const std::string& path, const std::string& case_name, const ObserverResult& r);

struct ValidateOptions {
  std::string tier = "quick";
  std::vector<std::string> cases;  ///< names; empty = every case under cases/
  std::string out_dir;
  std::string cases_dir;           ///< default: <source>/cases
  std::string baselines_dir;       ///< default: <source>/reference/baselines
  bool plots = true;
  bool pictures = true;            ///< each case's filmstrip (with plots; --no-pictures): its finest run writes frames, `render` draws them
  double max_particles = kDefaultMaxParticles;     ///< estimated particles above which a run is refused (--max-particles)
  bool errata = false;             ///< also run each erratum's printed form on its cases (--errata; validation/errata.hpp)
  bool convergence = false;        ///< run the cases' convergence studies instead of a tier (--convergence; validation/convergence.hpp)
  /// Methods to run each case with (--method), each one the case supports, in this order; empty:
  /// the case's own "method"; {"all"}: the tier's "methods" where it lists them, else the case's own
  /// method, then every one under its "methods".
  std::vector<std::string> methods;
};

/// The methods `options.methods` asks of a case that it supports, in the order asked (its own
/// method when none is asked; for "all", the methods of the tier). Empty when the case supports none
/// of them.
std::vector<std::string> methods_to_run(const CaseSpec& spec, const ValidateOptions& options);

/// Where a case's run by `method` lives: "<case>" for the case's own method, "<case>.<method>"
/// for another (its output folder under the run, and its baseline file's name).
std::string run_id(const CaseSpec& spec, const std::string& method);

/// The validation suite; returns the exit code (0 only if every case passed).
int validate(const ValidateOptions& options);

/// Case files found under a folder (<dir>/<name>/case.json), sorted by name.
std::vector<std::string> discover_cases(const std::string& cases_dir);

}  // namespace sc
