#include "dry_twin_report.hpp"

#include <algorithm>

#include "twin_run.hpp"

namespace sc {

namespace {

/// The case without its water blocks (the sand and its porous section stay).
CaseSpec without_water(const CaseSpec& spec) {
  CaseSpec dry = spec;
  std::erase_if(dry.blocks, [](const BlockSpec& b) { return b.fill == BlockFill::Water; });
  std::erase_if(dry.meshes, [](const MeshSpec& m) { return m.phase == Phase::Water; });
  return dry;
}

}  // namespace

void add_dry_twin_results(const CaseSpec& spec, double dx, const RunSettings& settings, RunResult& run) {
  if (!spec.validation.contains("dry_twin")) return;
  JsonObject o(spec.validation, "/validation", spec.file);
  JsonObject block = o.object("dry_twin");
  const std::vector<std::string> metrics = twin_names(block, "metrics"), series = twin_names(block, "series");
  block.finish();
  const auto limits = read_metric_limits(o);
  RunResult dry;
  if (!run_twin(without_water(spec), dx, settings, "dry", "dry twin", run, dry)) return;
  ObserverResult& r = run.observed;
  for (const std::string& n : metrics) {
    if (!r.metrics.count(n) || !dry.observed.metrics.count(n))
      throw InputError(spec.file, "/validation/dry_twin/metrics", "the observer computes no metric named " + n);
    add_metric(r, limits, n + "_dry", dry.observed.metrics.at(n).value);
    add_metric(r, limits, n + "_gain", r.metrics.at(n).value - dry.observed.metrics.at(n).value);
  }
  for (const std::string& n : series) {
    const Series* theirs = find_series(dry.observed, n);
    if (!theirs || !find_series(r, n))
      throw InputError(spec.file, "/validation/dry_twin/series", "the observer writes no series named " + n);
    overlay_twin(*theirs, n, "dry", "dry twin (no water)", r);
  }
  for (const auto& [name, metric] : r.metrics)
    if (!metric.pass() && run.status == "pass") run.status = "fail", run.exit_code = kCaseFailed;
}

}  // namespace sc
