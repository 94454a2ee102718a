// The Python scripts of reports/ (matplotlib plots, HTML pages) run by the command.
#pragma once
#include <string>
#include <vector>

namespace sc {

/// Runs /usr/bin/python3 <source>/reports/<script> with `args`; on failure prints a warning (the
/// JSON and Markdown outputs are complete without it) and returns false.
bool run_report_script(const std::string& script, const std::vector<std::string>& args);

}  // namespace sc
