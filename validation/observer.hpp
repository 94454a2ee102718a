// Observers record what a validation case measures while it runs, and turn it into metrics
// (compared with limits from the case file), time series and plot descriptions.
//
// A case file names its observer in "validation": {"observer": NAME, ...}; the observer reads the
// rest of that object itself (with JsonObject, so unknown keys are errors). To add one, write
// observers/<name>.cpp and list it in observers/registry.cpp.
//
// Observers see a run only through Method<D> (solver/method/method.hpp) and measure through its
// ParticleView, so every method is measured the same way; the few measurements that need what only
// SPH has go through the SPH probe (solver/simulator/sph_probe.hpp), which the observer checks for
// when it is built.
#pragma once
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "case/case_file.hpp"
#include "method/method.hpp"

namespace sc {

/// A limit on a metric: value <= max and/or value >= min. No bound: informational only.
struct MetricLimit {
  std::optional<double> min, max;
  bool accepts(double v) const { return std::isfinite(v) && (!min || v >= *min) && (!max || v <= *max); }
  json to_json() const;
};

struct Metric {
  double value = 0.0;
  MetricLimit limit;
  bool pass() const { return limit.accepts(value); }
};

struct Series {
  std::string name, x_label, y_label;
  std::vector<double> x, y;
};

struct Curve {
  std::string series, label, style;  // style: "line" or "markers"
};

struct Plot {
  std::string file, title, x_label, y_label;
  std::vector<Curve> curves;
  bool log_log = false;  ///< both axes logarithmic (convergence plots)
};

struct ObserverResult {
  std::map<std::string, Metric> metrics;
  std::vector<Series> series;
  std::vector<Plot> plots;
};

/// Reads "metrics": {"name": {"min": a, "max": b}} of a validation block.
std::map<std::string, MetricLimit> read_metric_limits(JsonObject& validation);

/// Records metric `name` with its limit from `limits` (informational if the case sets none).
void add_metric(ObserverResult& r, const std::map<std::string, MetricLimit>& limits, const std::string& name,
                double value);

/// A short human form of a number (printf %g).
std::string format_number(double v);

/// The series named `name` of r, or nullptr.
const Series* find_series(const ObserverResult& r, const std::string& name);

/// Whether a series is simulated (its name holds "_sim"), as opposed to a reference or exact curve.
bool is_simulated(const Series& s);

template <int D>
class Observer {
 public:
  virtual ~Observer() = default;
  /// Called once before the first step and after every step.
  virtual void sample(const Method<D>& run) = 0;
  /// Called at the end of the run; computes metrics against the reference.
  virtual ObserverResult finish(const Method<D>& run) = 0;
};

/// Context an observer is built with: the case, the spacing of this run, repository root.
struct ObserverContext {
  const CaseSpec& spec;
  double spacing;
  std::string source_dir;
};

/// The case's "validation" object with the keys the runner reads ("observer", "convergence")
/// marked as read, for an observer to read its own keys from.
JsonObject validation_block(const ObserverContext& ctx);

/// Builds the observer the case names; throws InputError for unknown names or bad parameters.
template <int D>
std::unique_ptr<Observer<D>> make_observer(const ObserverContext& ctx);

}  // namespace sc
