#include "runner.hpp"

#include <omp.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "adaptive_report.hpp"
#include "data_root.hpp"
#include "dry_twin_report.hpp"
#include "io/atomic_file.hpp"
#include "io/vtu_writer.hpp"
#include "method/registry.hpp"
#include "progress.hpp"
#include "report.hpp"
#include "restart.hpp"
#include "parallel/comm.hpp"
#include "simulator/sph_probe.hpp"
#include "surface/surface_mesh.hpp"

namespace fs = std::filesystem;

namespace sc {

std::string surface_file_name(Phase phase, std::size_t frame) {
  char name[48];
  std::snprintf(name, sizeof name, "surface_%s_%05zu.vtp", std::string(phase_name(phase)).c_str(), frame);
  return name;
}

namespace {

/// surface_<phase>_NNNNN.vtp of frame k: the surface of the particles of each phase of water and
/// sand that has any, for the spacing dx (surface/surface_mesh.hpp); the sand's carries the
/// particles' saturation where the method has one.
void write_surfaces(const ParticleView<3>& view, double dx, const std::string& dir, std::size_t frame) {
  for (const Phase phase : {Phase::Water, Phase::Sand}) {
    std::vector<Vec<3>> x;
    std::vector<double> saturation;
    const bool wet = phase == Phase::Sand && !view.saturation.empty();
    for (std::size_t i = 0; i < view.size(); ++i)
      if (view.phase_of(i) == phase) {
        x.push_back(view.x[i]);
        if (wet) saturation.push_back(view.saturation[i]);
      }
    if (x.empty()) continue;
    surface::SurfaceMesh mesh = surface::reconstruct_surface(x, {.spacing = dx});
    if (wet) surface::attach_saturation(mesh, x, saturation, {.spacing = dx});
    write_file_atomic(dir + "/" + surface_file_name(phase, frame), surface::vtp_document(mesh));
  }
}

template <int D>
RunResult run_in_dimension(const CaseSpec& spec, double dx, const RunSettings& settings) {
  // Decomposed, every rank computes and rank 0 writes; whatever may fail on one rank (reading the
  // start, rank 0's files) runs in run_agreed, so an error there stops every rank alike.
  const Comm ranks = settings.decompose ? Comm::world() : Comm();
  const bool writer = ranks.rank() == 0;
  const ObserverContext ctx{spec, dx, data_root()};
  std::unique_ptr<Observer<D>> observer;
  FrameLog log;
  std::unique_ptr<Method<D>> method;
  run_agreed(ranks, [&] {  // no collective: the scene is decomposed without one (Decomposition::scatter)
    observer = make_observer<D>(ctx);  // checks the validation block first
    method = start_method<D>(spec, dx, settings.resume_from, log, settings.decompose);
    if (writer) fs::create_directories(settings.out_dir);
  });
  Method<D>& run = *method;
  RunResult result;
  result.spacing = dx;
  result.particles = run.particles().size();
  const double end = settings.end_time > 0.0 ? settings.end_time : spec.end_time;

  auto& frames = log.frames;
  double& next_frame = log.next_frame;
  const auto surfaces_of = [&](std::size_t frame) {  // the surface files written beside a frame
    std::vector<std::string> files;
    for (const Phase phase : {Phase::Water, Phase::Sand})
      if (fs::exists(settings.out_dir + "/" + surface_file_name(phase, frame))) files.push_back(surface_file_name(phase, frame));
    return files;
  };
  auto write_frame = [&]() {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%05zu.vtu", frames.size());
    const std::string frame = run.vtu_frame();  // collective when decomposed
    const ParticleView<D> view = run.particles();
    frames.emplace_back(run.time(), name);
    run_agreed(ranks, [&] {
      if (!writer) return;
      write_file_atomic(settings.out_dir + "/" + name, frame);
      if constexpr (D == 3)
        if (settings.write_surfaces) write_surfaces(view, dx, settings.out_dir, frames.size() - 1);
      write_file_atomic(settings.out_dir + "/frames.pvd", pvd_document(frames, surfaces_of));
    });
  };
  // The checkpoint gathers the state, then rank 0 writes it.
  auto write_checkpoint = [&](const std::string& name) {
    run_agreed(ranks, [&] { write_run_checkpoint(settings.out_dir + "/" + name, run, log); });
  };

  const auto start = std::chrono::steady_clock::now();
  Progress progress(settings.label, end, writer ? Progress::Shown::yes : Progress::Shown::no);  // decomposed: rank 0's
  observer->sample(run);
  auto count_moving = [&]() {
    const ParticleView<D> view = run.particles();
    long n = 0;
    for (std::size_t i = 0; i < view.size(); ++i) n += view.moves(i) ? 1 : 0;
    result.moving_particles.x.push_back(run.time());
    result.moving_particles.y.push_back(static_cast<double>(n));
  };
  count_moving();
  try {
    if (settings.write_frames && frames.empty()) write_frame();
    while (run.time() < end - 1e-12) {
      run.step();  // an error on one rank inside it ends the job (main's last resort)
      run_agreed(ranks, [&] {  // the observer's one collective, the gather of the state, comes first
        observer->sample(run);
        count_moving();
      });
      if (settings.write_frames && spec.frame_interval > 0.0 && run.time() >= next_frame + spec.frame_interval - 1e-12) {
        next_frame += spec.frame_interval;
        write_frame();
      }
      if (settings.checkpoint_every > 0 && run.steps() % settings.checkpoint_every == 0) write_checkpoint(checkpoint_name(run.steps()));
      progress.update(run.time(), run.steps());
    }
    if (settings.write_frames && (frames.empty() || frames.back().first < run.time())) write_frame();
    progress.done(run.time(), run.steps());
  } catch (const BlowUpError& e) {
    progress.done(run.time(), run.steps());
    const std::string last_good = run.last_good_frame();  // collective when decomposed
    run_agreed(ranks, [&] {
      if (writer) write_file_atomic(settings.out_dir + "/last_good.vtu", last_good);
    });
    std::string saved = settings.out_dir + "/last_good.vtu";
    if (run.writes_checkpoints()) {
      write_checkpoint("last_good.ckpt");
      saved += " and " + settings.out_dir + "/last_good.ckpt";
    }
    result.status = "error";
    result.exit_code = kBlowUp;
    result.message = std::string(e.what()) + "; last good state in " + saved;
  }
  result.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.steps = run.steps();
  result.checksum = run.checksum();
  const auto& counts = result.moving_particles.y;
  for (double c : counts) result.moving_particles_mean += c / static_cast<double>(counts.size());
  if (spec.adaptive) result.adapt = require_sph(run, "the adaptivity report").adapt_account();
  if (settings.decompose) result.decomposition = require_sph(run, "the decomposition's account").decomposition();
  if (result.status != "error") {
    const std::string final_frame = run.vtu_frame();  // collective when decomposed
    run_agreed(ranks, [&] {
      if (writer) write_file_atomic(settings.out_dir + "/final.vtu", final_frame);
      result.observed = observer->finish(run);
    });
    for (const auto& [name, metric] : result.observed.metrics)
      if (!metric.pass()) result.status = "fail";
    result.exit_code = result.status == "pass" ? kSuccess : kCaseFailed;
  }
  return result;
}

/// Checks what the run asks of its method before anything is allocated: a known method, SPH for
/// split and merge, checkpoints when the run writes or resumes one.
void check_run(const CaseSpec& spec, const RunSettings& settings) {
  check_method(spec);
  if (settings.decompose) check_decomposable(spec);
  if (spec.adaptive) require_sph(spec, "the \"adaptive\" section (split and merge)");
  if ((settings.checkpoint_every > 0 || !settings.resume_from.empty()) && !method_writes_checkpoints(spec.method))
    throw InputError(spec.file, "/method", "--checkpoint-every and --resume are not supported by method \"" +
                                               spec.method + "\" (it writes no checkpoints)");
}

}  // namespace

RunResult run_single(const CaseSpec& spec, double dx, const RunSettings& settings) {
  check_run(spec, settings);
  return spec.dimension == 2 ? run_in_dimension<2>(spec, dx, settings) : run_in_dimension<3>(spec, dx, settings);
}

RunResult run_simulation(const CaseSpec& spec, double dx, const RunSettings& settings) {
  RunResult r = run_single(spec, dx, settings);
  if (spec.adaptive && r.status != "error") add_adaptive_results(spec, dx, settings, r);
  if (r.status != "error") add_dry_twin_results(spec, dx, settings, r);
  return r;
}

void write_series_file(const std::string& path, const std::string& case_name, const ObserverResult& r) {
  json series = json::array(), plots = json::array();
  for (const Series& s : r.series)
    series.push_back({{"name", s.name}, {"x_label", s.x_label}, {"y_label", s.y_label}, {"x", s.x}, {"y", s.y}});
  for (const Plot& p : r.plots) {
    json curves = json::array();
    for (const Curve& c : p.curves) curves.push_back({{"series", c.series}, {"label", c.label}, {"style", c.style}});
    plots.push_back({{"file", p.file}, {"title", p.title}, {"x_label", p.x_label}, {"y_label", p.y_label}, {"curves", curves}});
    if (p.log_log) plots.back()["log_log"] = true;
  }
  write_file_atomic(path, json{{"case", case_name}, {"series", series}, {"plots", plots}}.dump(1) + "\n");
}

std::vector<std::string> discover_cases(const std::string& cases_dir) {
  std::vector<std::string> out;
  if (!fs::is_directory(cases_dir)) throw InputError(cases_dir, "", "cases folder not found");
  for (const auto& entry : fs::directory_iterator(cases_dir))
    if (entry.is_directory() && fs::exists(entry.path() / "case.json")) out.push_back((entry.path() / "case.json").string());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace sc
