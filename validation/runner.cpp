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
#include "progress.hpp"
#include "report.hpp"
#include "restart.hpp"
#include "scene/scene_builder.hpp"

namespace fs = std::filesystem;

namespace sc {

namespace {

template <int D>
RunResult run_in_dimension(const CaseSpec& spec, double dx, const RunSettings& settings) {
  const ObserverContext ctx{spec, dx, data_root()};
  std::unique_ptr<Observer<D>> observer = make_observer<D>(ctx);  // checks the validation block first
  FrameLog log;
  Simulator<D> sim = start_simulator<D>(spec, dx, settings.resume_from, log);
  RunResult result;
  result.spacing = dx;
  result.particles = sim.particles().size();
  const double end = settings.end_time > 0.0 ? settings.end_time : spec.end_time;
  fs::create_directories(settings.out_dir);

  auto& frames = log.frames;
  double& next_frame = log.next_frame;
  auto write_frame = [&]() {
    auto t = sim.timers().time(Stage::Output);
    char name[32];
    std::snprintf(name, sizeof name, "frame_%05zu.vtu", frames.size());
    write_file_atomic(settings.out_dir + "/" + name, vtu_document(sim.particles()));
    frames.emplace_back(sim.time(), name);
    write_file_atomic(settings.out_dir + "/frames.pvd", pvd_document(frames));
  };

  const auto start = std::chrono::steady_clock::now();
  Progress progress(settings.label, end);
  observer->sample(sim);
  auto count_moving = [&]() {
    const auto& ps = sim.particles();
    long n = 0;
    for (std::size_t i = 0; i < ps.size(); ++i) n += ps.moves(i) ? 1 : 0;
    result.moving_particles.x.push_back(sim.time());
    result.moving_particles.y.push_back(static_cast<double>(n));
  };
  count_moving();
  try {
    if (settings.write_frames && frames.empty()) write_frame();
    while (sim.time() < end - 1e-12) {
      sim.step();
      observer->sample(sim);
      count_moving();
      if (settings.write_frames && spec.frame_interval > 0.0 && sim.time() >= next_frame + spec.frame_interval - 1e-12) {
        next_frame += spec.frame_interval;
        write_frame();
      }
      if (settings.checkpoint_every > 0 && sim.steps() % settings.checkpoint_every == 0)
        write_run_checkpoint(settings.out_dir + "/" + checkpoint_name(sim.steps()), sim, spec, dx, log);
      progress.update(sim.time(), sim.steps());
    }
    if (settings.write_frames && (frames.empty() || frames.back().first < sim.time())) write_frame();
    progress.done(sim.time(), sim.steps());
  } catch (const BlowUpError& e) {
    progress.done(sim.time(), sim.steps());
    write_file_atomic(settings.out_dir + "/last_good.vtu", vtu_document(sim.particles()));
    write_run_checkpoint(settings.out_dir + "/last_good.ckpt", sim, spec, dx, log);
    result.status = "error";
    result.exit_code = kBlowUp;
    result.message = std::string(e.what()) + "; last good state in " + settings.out_dir + "/last_good.vtu and " +
                     settings.out_dir + "/last_good.ckpt";
  }
  result.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.steps = sim.steps();
  result.checksum = sim.particles().checksum();
  const auto& counts = result.moving_particles.y;
  for (double c : counts) result.moving_particles_mean += c / static_cast<double>(counts.size());
  if (spec.adaptive) result.adapt = sim.adapt_account();
  if (result.status != "error") {
    write_file_atomic(settings.out_dir + "/final.vtu", vtu_document(sim.particles()));
    result.observed = observer->finish(sim);
    for (const auto& [name, metric] : result.observed.metrics)
      if (!metric.pass()) result.status = "fail";
    result.exit_code = result.status == "pass" ? kSuccess : kCaseFailed;
  }
  return result;
}

}  // namespace

RunResult run_simulation(const CaseSpec& spec, double dx, const RunSettings& settings) {
  RunResult r = spec.dimension == 2 ? run_in_dimension<2>(spec, dx, settings) : run_in_dimension<3>(spec, dx, settings);
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
