// Regression baselines (reference/baselines/<case>.json): writing them from a finished run
// (`sandcastle baseline`, an explicit act) and comparing a validation run with them
// (`sandcastle validate`, report.json "baseline" per case). Format: reports/README.md.
#pragma once
#include <string>
#include <vector>

#include "case/case_file.hpp"
#include "io/json_reader.hpp"
#include "runner.hpp"

namespace sc {

/// The folder baselines live in: `options.baselines_dir`, or <source>/reference/baselines.
std::string baselines_folder(const ValidateOptions& options);

/// The build that made this binary: {"compiler", "flags"}.
json build_identity();

/// The baseline document of a report.json case entry (series from run_dir), with provenance taken
/// from the report header, the entry and `date`.
json baseline_document(const json& report, const json& entry, const std::string& run_dir, const std::string& date);

/// Compares the case entry of a validation run (its series already in run_dir) with the case's
/// baseline in `baselines_dir`: the "baseline" object of report.json. Throws InputError when the
/// case's "regression" limits name a series or metric the run does not have.
json compare_with_baseline(const CaseSpec& spec, const json& entry, const std::string& run_dir,
                           const std::string& baselines_dir);

/// Adds "parameters_hash" and "baseline" to a validation entry; a regression raises the exit code
/// to kCaseFailed like a failed physics gate.
void add_baseline_comparison(const CaseSpec& spec, const ValidateOptions& options, json& entry, int& exit_code);

/// Writes baselines_dir/<run id>.json (runner.hpp run_id: <case>.json for the case's own method,
/// <case>.<method>.json for another) for the runs of run_dir/report.json: only the cases in
/// `names` if not empty; only the methods in `methods` ({"all"}: every method; empty: each case's
/// own). Runs that stopped with an error get none. Returns the exit code: 0, or 2 when a named
/// case is not in the run or a run could not be blessed.
int write_baselines(const std::string& run_dir, const std::string& baselines_dir, const std::vector<std::string>& names,
                    const std::vector<std::string>& methods = {});

/// The "Baselines" section of summary.md.
std::string baseline_markdown(const json& report);

/// summary.baseline of report.json: how many cases are identical, changed, regressed, missing.
json baseline_counts(const std::vector<json>& cases);

}  // namespace sc
