#include "adaptive_report.hpp"

#include <algorithm>

#include "run_record.hpp"
#include "twin_run.hpp"

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

std::string metric_stem(const std::string& series) {
  const auto at = series.rfind("_sim");
  return at == std::string::npos ? series : series.substr(0, at) + series.substr(at + 4);
}

struct TwinRequest {
  std::vector<std::string> series, metrics;
  int ensemble = 1;  ///< adaptive runs whose median enters the metric ratios (1: the run itself)
};

/// The value of metric `name` for the ratio against the twin: the run's own, or with an ensemble of
/// n > 1 the median over the run and n − 1 copies whose split offset is nudged by k·1e-5
/// (relative, k = 1 … n − 1). A metric of a resting arrangement left by splits and merges is a
/// chaotic function of round-off: a nudge of the split offset in its fifth digit, or a slightly
/// longer relaxation, can move split_merge's pressure L2 by a large factor, so one run cannot decide
/// a ratio gate; the median of a few can. The ensemble's
/// spread is reported as <name>_ensemble_min / _max.
double ensemble_value(const CaseSpec& spec, double dx, const RunSettings& settings, int n, const std::string& name,
                      std::vector<ObserverResult>& copies, RunResult& run) {
  if (n <= 1) return run.observed.metrics.at(name).value;
  for (int k = static_cast<int>(copies.size()) + 1; k < n; ++k) {
    CaseSpec nudged = spec;
    nudged.adaptive->params.split_offset *= 1.0 + 1e-5 * k;
    RunResult copy;
    if (!run_twin(nudged, dx, settings, "ensemble_" + std::to_string(k), "ensemble run " + std::to_string(k), run, copy))
      return run.observed.metrics.at(name).value;
    copies.push_back(copy.observed);
  }
  std::vector<double> v{run.observed.metrics.at(name).value};
  for (const ObserverResult& c : copies) v.push_back(c.metrics.at(name).value);
  std::sort(v.begin(), v.end());
  const auto limits = case_limits(spec);
  add_metric(run.observed, limits, name + "_ensemble_min", v.front());
  add_metric(run.observed, limits, name + "_ensemble_max", v.back());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

void compare_with_twin(const CaseSpec& spec, double dx, const RunSettings& settings, const TwinRequest& request,
                       const std::map<std::string, MetricLimit>& limits, RunResult& run) {
  CaseSpec uniform = spec;
  uniform.adaptive.reset();
  RunResult twin;
  if (!run_twin(uniform, dx, settings, "uniform", "uniform twin", run, twin)) return;
  ObserverResult& r = run.observed;
  for (const std::string& n : request.series) {
    const Series* mine = find_series(r, n);
    const Series* theirs = find_series(twin.observed, n);
    if (!mine || !theirs)
      throw InputError(spec.file, "/validation/uniform_twin/series", "the observer writes no series named " + n);
    add_metric(r, limits, metric_stem(n) + "_vs_uniform_rms", series_difference(*theirs, *mine).relative_rms);
    overlay_twin(*theirs, n, "uniform", "uniform (no adaptivity)", r);
  }
  std::vector<ObserverResult> copies;
  for (const std::string& n : request.metrics) {
    if (!r.metrics.count(n) || !twin.observed.metrics.count(n))
      throw InputError(spec.file, "/validation/uniform_twin/metrics", "the observer computes no metric named " + n);
    const double value = ensemble_value(spec, dx, settings, request.ensemble, n, copies, run);
    add_metric(r, limits, n + "_vs_uniform_ratio", value / twin.observed.metrics.at(n).value);
  }
  add_metric(r, limits, "particle_ratio", twin.moving_particles_mean / run.moving_particles_mean);
  add_metric(r, limits, "uniform_moving_particles_mean", twin.moving_particles_mean);
  overlay_twin(twin.moving_particles, "moving_particles", "uniform", "uniform (no adaptivity)", r);
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
    TwinRequest request{twin_names(twin, "series"), twin_names(twin, "metrics")};
    request.ensemble = static_cast<int>(twin.integer("ensemble", 1, 9, 1));
    twin.finish();
    compare_with_twin(spec, dx, settings, request, limits, run);
  }
  for (const auto& [name, metric] : r.metrics)
    if (!metric.pass() && run.status == "pass") run.status = "fail", run.exit_code = kCaseFailed;
}

}  // namespace sc
