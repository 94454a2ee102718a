// One case run by several methods, side by side (`sandcastle validate --method sph,flip`): for each
// case that more than one method ran, a table of every metric per method beside its gate, and
// overlay plots of each observable by every method against the same reference. report.json
// "methods" (reports/README.md); summary.md and report.html show it.
#pragma once
#include <string>
#include <vector>

#include "case/case_file.hpp"
#include "io/json_reader.hpp"
#include "observer.hpp"

namespace sc {

/// One method's run of a case: its report.json entry and what its finest run observed.
struct MethodRun {
  std::string method;
  json entry;
  ObserverResult observed;
};

/// The comparison of `runs` (two or more methods on the case `spec`): the "methods" item of
/// report.json. Writes the overlay series to <out_dir>/<first run's id>/methods.json, whose plots
/// (methods_<plot>.png) the plotting script draws.
json methods_comparison(const CaseSpec& spec, const std::vector<MethodRun>& runs, const std::string& out_dir);

/// The methods plots of a comparison: each plot of the first run with every simulated series
/// ("*_sim*") once per method, renamed <series>@<method>, and the reference curves once.
ObserverResult methods_overlay(const std::vector<MethodRun>& runs);

/// summary.md's side-by-side tables (empty when the report has no "methods").
std::string methods_markdown(const json& report);

}  // namespace sc
