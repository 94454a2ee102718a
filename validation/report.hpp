// report.json (schema_version 1, docs/architecture.md "Contracts": extend it, never rename a field),
// summary.md, and the call to the plotting script.
#pragma once
#include <string>
#include <vector>

#include "io/json_reader.hpp"
#include "runner.hpp"

namespace sc {

/// The report entry of one case from its runs (one per spacing, coarse to fine). The finest run
/// supplies the fields of the contract; every run is listed under "resolutions".
json case_entry(const CaseSpec& spec, const std::string& tier, const std::vector<RunResult>& runs,
                const std::string& series_file, const std::vector<std::string>& plot_files);

/// An entry for a case that could not be run (bad input): status "error" with the message.
json error_entry(const std::string& name, const std::string& tier, const std::string& message);

/// The whole report: header fields, the case entries and the summary counts.
json report_document(const std::vector<json>& cases);

/// summary.md: a short table for terminals and CI logs.
std::string summary_markdown(const json& report);

/// The "Filmstrips" section of summary.md: each case's filmstrip (report.json "filmstrip") as an
/// image link, or why it has none ("filmstrip_note"); empty when no case has either.
std::string filmstrip_markdown(const json& report);

/// The current commit of the source tree ("unknown" outside a checkout).
std::string git_commit();

}  // namespace sc
