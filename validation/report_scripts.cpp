#include "data_root.hpp"
#include "report_scripts.hpp"

#include <cstdlib>
#include <iostream>

namespace sc {

namespace {

/// A shell word: single quotes, with embedded single quotes escaped.
std::string quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace

bool run_report_script(const std::string& script, const std::vector<std::string>& args) {
  std::string cmd = "/usr/bin/python3 " + quoted(data_path("reports/" + script));
  for (const std::string& a : args) cmd.append(" ").append(quoted(a));  // not " " + ...: GCC 12 -O3 warns falsely (-Wrestrict)
  if (std::system(cmd.c_str()) == 0) return true;
  std::cerr << "warning: reports/" << script << " failed (needs python3-matplotlib); the JSON and Markdown reports are complete\n";
  return false;
}

}  // namespace sc
