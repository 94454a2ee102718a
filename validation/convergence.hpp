// Convergence studies (`sandcastle validate --convergence`): a case that lists
// "convergence": {"spacings": [...], "metrics": {NAME: order}} is run at each spacing, by each
// method asked of it, and each named metric (an error against the case's reference) is reported at
// every spacing with its observed order, the least-squares slope of log(error) against
// log(spacing), beside the order the method should reach. Each run is one task of the sweep
// (validation/sweep.hpp), so a study spreads over MPI ranks. Orders are reported, not gated: the
// gates of a case are its tiers'.
#pragma once
#include <string>
#include <vector>

#include "io/json_reader.hpp"
#include "runner.hpp"

namespace sc {

/// The least-squares slope of log(error) against log(spacing) over the pairs whose error is finite
/// and positive; NaN when fewer than two such pairs have distinct spacings.
double observed_order(const std::vector<double>& spacings, const std::vector<double>& errors);

/// Runs the studies of the cases in `files` that have one, every run a task of the sweep. On rank
/// 0: writes DIR/convergence/<run id>/series.json (per metric a log-log plot of its error against
/// the spacing, with the line of the expected order through the finest point) and returns the
/// report's "convergence" entries, one per case and method (reports/README.md); raises `exit_code`
/// to that of a run that failed. Other ranks return null.
json run_convergence(const std::vector<std::string>& files, const ValidateOptions& opt, int& exit_code);

/// The summary.md section of the report's "convergence" entries ("" without any).
std::string convergence_markdown(const json& report);

}  // namespace sc
