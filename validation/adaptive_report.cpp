#include "adaptive_report.hpp"

#include "run_record.hpp"

namespace sc {

namespace {

std::map<std::string, MetricLimit> case_limits(const CaseSpec& spec) {
  JsonObject o(spec.validation, "/validation", spec.file);
  return read_metric_limits(o);
}

void add_account(const AdaptAccount& a, const std::map<std::string, MetricLimit>& limits, ObserverResult& r) {
  add_metric(r, limits, "adaptive_mass_rel_error", a.max_mass_rel_error);
  add_metric(r, limits, "adaptive_momentum_error", a.max_momentum_error);
  add_metric(r, limits, "adaptive_moment_error", a.max_moment_error);
  add_metric(r, limits, "adaptive_water_rel_error", a.max_water_rel_error);
  add_metric(r, limits, "merge_energy_removed", a.energy_removed);
  add_metric(r, limits, "splits", static_cast<double>(a.splits));
  add_metric(r, limits, "merges", static_cast<double>(a.merges));
}

const Series* find_series(const ObserverResult& r, const std::string& name) {
  for (const Series& s : r.series)
    if (s.name == name) return &s;
  return nullptr;
}

std::string metric_stem(const std::string& series) {
  const auto at = series.rfind("_sim");
  return at == std::string::npos ? series : series.substr(0, at) + series.substr(at + 4);
}

/// The twin's copy of `name` joins the series and every plot that shows `name`.
void overlay_twin(const Series& twin, const std::string& name, ObserverResult& r) {
  Series renamed = twin;
  renamed.name = "uniform_" + name;
  r.series.push_back(renamed);
  for (Plot& p : r.plots)
    for (std::size_t c = 0, n = p.curves.size(); c < n; ++c)
      if (p.curves[c].series == name) p.curves.push_back({renamed.name, "uniform (no adaptivity)", "line"});
}

/// Names the "uniform_twin" block lists under `key` (an array of strings).
std::vector<std::string> twin_names(JsonObject& twin, const std::string& key) {
  std::vector<std::string> names;
  if (!twin.has(key)) return names;
  for (const json& name : twin.raw(key)) {
    if (!name.is_string()) twin.fail(key, "must be an array of names (strings)");
    names.push_back(name.get<std::string>());
  }
  return names;
}

struct TwinRequest {
  std::vector<std::string> series, metrics;
};

void compare_with_twin(const CaseSpec& spec, double dx, const RunSettings& settings, const TwinRequest& request,
                       const std::map<std::string, MetricLimit>& limits, RunResult& run) {
  CaseSpec uniform = spec;
  uniform.adaptive.reset();
  RunSettings twin_settings;
  twin_settings.out_dir = settings.out_dir + "/uniform";
  twin_settings.end_time = settings.end_time;
  twin_settings.label = settings.label + " (uniform twin)";
  const RunResult twin = run_simulation(uniform, dx, twin_settings);
  if (twin.status == "error") {
    run.status = "error";
    run.exit_code = twin.exit_code;
    run.message = "uniform twin: " + twin.message;
    return;
  }
  ObserverResult& r = run.observed;
  for (const std::string& n : request.series) {
    const Series* mine = find_series(r, n);
    const Series* theirs = find_series(twin.observed, n);
    if (!mine || !theirs)
      throw InputError(spec.file, "/validation/uniform_twin/series", "the observer writes no series named " + n);
    add_metric(r, limits, metric_stem(n) + "_vs_uniform_rms", series_difference(*theirs, *mine).relative_rms);
    overlay_twin(*theirs, n, r);
  }
  for (const std::string& n : request.metrics) {
    if (!r.metrics.count(n) || !twin.observed.metrics.count(n))
      throw InputError(spec.file, "/validation/uniform_twin/metrics", "the observer computes no metric named " + n);
    add_metric(r, limits, n + "_vs_uniform_ratio", r.metrics.at(n).value / twin.observed.metrics.at(n).value);
  }
  add_metric(r, limits, "particle_ratio", twin.moving_particles_mean / run.moving_particles_mean);
  add_metric(r, limits, "wall_time_ratio", twin.wall_seconds / run.wall_seconds);
  add_metric(r, limits, "uniform_wall_seconds", twin.wall_seconds);
  add_metric(r, limits, "uniform_moving_particles_mean", twin.moving_particles_mean);
  overlay_twin(twin.moving_particles, "moving_particles", r);
}

}  // namespace

void add_adaptive_results(const CaseSpec& spec, double dx, const RunSettings& settings, RunResult& run) {
  const auto limits = case_limits(spec);
  ObserverResult& r = run.observed;
  if (run.adapt) add_account(*run.adapt, limits, r);
  add_metric(r, limits, "moving_particles_mean", run.moving_particles_mean);
  r.series.push_back(run.moving_particles);
  r.plots.push_back({"particles.png", "Moving particles", "time [s]", "particles",
                     {{"moving_particles", "adaptive", "line"}}});
  if (spec.validation.contains("uniform_twin")) {
    JsonObject o(spec.validation, "/validation", spec.file);
    JsonObject twin = o.object("uniform_twin");
    const TwinRequest request{twin_names(twin, "series"), twin_names(twin, "metrics")};
    twin.finish();
    compare_with_twin(spec, dx, settings, request, limits, run);
  }
  for (const auto& [name, metric] : r.metrics)
    if (!metric.pass() && run.status == "pass") run.status = "fail", run.exit_code = kCaseFailed;
}

}  // namespace sc
