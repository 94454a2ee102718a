// Twin runs: the runner re-runs a case with one ingredient removed (adaptivity: the "uniform_twin";
// the water: the "dry_twin") and compares the two. What both comparisons share lives here.
#pragma once
#include <string>
#include <vector>

#include "case/case_file.hpp"
#include "runner.hpp"

namespace sc {

/// Runs `twin` at dx into <settings.out_dir>/<subdir> (run_single: the twin starts no twins of its
/// own). On a blow-up or error of the twin, marks
/// `run` as an error (message prefixed with `what`) and returns false.
bool run_twin(const CaseSpec& twin, double dx, const RunSettings& settings, const std::string& subdir,
              const std::string& what, RunResult& run, RunResult& twin_result);

/// The twin's copy of series `name` joins r as <prefix>_<name>, with label `label` on every plot
/// that shows `name`.
void overlay_twin(const Series& twin, const std::string& name, const std::string& prefix, const std::string& label,
                  ObserverResult& r);

/// Names a twin block lists under `key` (an array of strings; none if absent).
std::vector<std::string> twin_names(JsonObject& twin, const std::string& key);

}  // namespace sc
