// The "regression" block of a case file: how far a run may move from its stored baseline
// (reference/baselines/<case>.json) before `sandcastle validate` calls it a regression, and the
// parameters hash that identifies the case's physics in a baseline's provenance.
#pragma once
#include <map>
#include <optional>
#include <string>

#include "io/json_reader.hpp"

namespace sc {

/// Limits on the difference between a run and its baseline; every limit set must hold.
/// For a series: relative = RMS of the difference / RMS of the baseline values, absolute = the
/// largest |difference|. For an end-state metric: relative = |delta| / |baseline|, absolute = |delta|.
struct DifferenceLimit {
  std::optional<double> relative, absolute;
  bool accepts(double relative_value, double absolute_value) const;
  json to_json() const;
};

struct RegressionSpec {
  DifferenceLimit series_default{0.02, std::nullopt};  ///< "series": {"*": ...}
  DifferenceLimit metric_default{0.1, std::nullopt};   ///< "metrics": {"*": ...}
  std::map<std::string, DifferenceLimit> series, metrics;  ///< by name; replaces the default

  const DifferenceLimit& for_series(const std::string& name) const;
  const DifferenceLimit& for_metric(const std::string& name) const;
};

/// Reads {"series": {NAME | "*": {"relative", "absolute"}}, "metrics": {...}}.
RegressionSpec read_regression(JsonObject o);

/// FNV-1a 64 of the case file's canonical JSON (keys sorted, no whitespace), leaving out what
/// does not change a run: "description", "regression", "convergence" (a study's spacings; each
/// run records its own), "comment", keys starting with '_', and "methods" (the parameters of methods other than the case's own: with_method in
/// method/registry.hpp mixes in those of the method a run uses).
/// 16 hex digits.
std::string parameters_hash(const json& case_document);

}  // namespace sc
