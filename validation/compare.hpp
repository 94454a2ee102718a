// `sandcastle compare RUN_A RUN_B --out DIR`: a diff of two validation runs. Per case both
// checksums, every metric of both runs with the delta, and the difference of every series;
// written as DIR/compare.json and DIR/compare.md, and with plots as DIR/compare.html and
// DIR/<case>/*.png (both runs' series overlaid with the reference). Format: reports/README.md.
#pragma once
#include <string>

#include "io/json_reader.hpp"

namespace sc {

/// The compare.json document of two run folders (each with a report.json).
json compare_document(const std::string& run_a, const std::string& run_b);

/// compare.md: a table per case for terminals and CI logs.
std::string compare_markdown(const json& doc);

/// Writes the comparison to out_dir; returns the exit code (0; bad input throws InputError).
int compare_runs(const std::string& run_a, const std::string& run_b, const std::string& out_dir, bool plots);

}  // namespace sc
