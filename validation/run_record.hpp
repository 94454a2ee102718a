// What the regression tools (baselines, `sandcastle compare`) know about one case of one run: its
// checksum, end-state metrics and observable series, read from a run folder (report.json entry +
// series.json) or from a baseline file; and the differences between two such records.
#pragma once
#include <map>
#include <string>
#include <vector>

#include "io/json_reader.hpp"
#include "observer.hpp"

namespace sc {

struct RunRecord {
  std::string name, tier, status, checksum, parameters_hash;
  double spacing = 0.0;
  std::map<std::string, double> metrics;  ///< NaN where the report has null
  std::vector<Series> series;
};

/// The record of a report.json case entry; its series come from run_dir/<entry.series>.
RunRecord record_from_entry(const json& entry, const std::string& run_dir);

/// The key of a report.json entry: its "run_id" (<case>, or <case>.<method> for a method other
/// than the case's own; runner.hpp run_id), or its "name" in reports written before methods.
std::string run_key(const json& entry);

/// The series of a series.json document (or of a baseline file, which stores them the same way).
std::vector<Series> series_from_json(const json& series_array, const std::string& file);

/// Difference of one series against another (`base`). The abscissa is x where x increases
/// strictly, else y where y does (profiles such as pressure against height), else the point index;
/// `other` is interpolated linearly onto the abscissae of `base` (end values beyond its range).
struct SeriesDelta {
  double relative_rms = 0.0;    ///< RMS(other - base) / RMS(base); 0/0 = 0, x/0 = inf
  double max_difference = 0.0;  ///< max |other - base|
  std::string note;             ///< why the series could not be compared (then both are inf)
};
SeriesDelta series_difference(const Series& base, const Series& other);

/// At most `max_points` points of a series with an increasing x or y (every k-th and the last),
/// for storing it in a baseline; other series are kept whole (they are compared point by point).
Series thinned(const Series& s, std::size_t max_points);

/// Difference of an end-state metric: delta = other - base, relative = |delta| / |base|.
/// null (NaN) against null is no difference; null against a number is an infinite one.
struct MetricDelta {
  double delta = 0.0, relative = 0.0;
};
MetricDelta metric_difference(double base, double other);

/// A number for JSON: null where it is not finite.
json finite_or_null(double v);

}  // namespace sc
