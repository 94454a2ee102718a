// `sandcastle validate --errata`: each erratum of the thesis that has a switch to its printed form
// (docs/equations.md §5) is run on the cases it affects, next to the normal (corrected) run, so the
// report shows what each erratum does: report.json's "errata" section (reports/README.md), a table
// in summary.md and in report.html.
#pragma once
#include <string>
#include <vector>

#include "io/json_reader.hpp"
#include "runner.hpp"

namespace sc {

/// One erratum with a switch: the equation, what the printed form does, the JSON merge patch
/// (RFC 7386) that selects the printed form in a case document, and the cases it affects.
struct Erratum {
  std::string equation;
  std::string printed;
  json patch;
  std::vector<std::string> cases;
};

/// The errata with switches and the cases each affects: the one table of it.
const std::vector<Erratum>& errata_table();

/// The case document at `file` with an erratum's patch merged in (the file itself is untouched).
json patched_case_document(const std::string& file, const json& patch);

/// Runs each erratum's printed form on the affected cases among `entries` (the normal run's case
/// entries, which give the corrected metrics) at the tier's finest spacing; returns the "errata"
/// section of report.json. Runs write under <out>/errata/<equation>/<case>.
json run_errata(const ValidateOptions& opt, const std::string& cases_dir, const std::vector<json>& entries);

/// The errata-impact table of summary.md (empty when the report has no "errata" section).
std::string errata_markdown(const json& report);

}  // namespace sc
