#include "report.hpp"

#include <omp.h>

#include <cstdio>
#include <sstream>

#include "baseline.hpp"
#include "run_record.hpp"

namespace sc {

namespace {

json metrics_json(const std::map<std::string, Metric>& metrics) {
  json out = json::object();
  for (const auto& [name, m] : metrics)
    out[name] = {{"value", std::isfinite(m.value) ? json(m.value) : json(nullptr)}, {"limit", m.limit.to_json()}, {"pass", m.pass()}};
  return out;
}

/// Convergence metrics for the names listed in validation.convergence: the ratio of the finest
/// run's error to the next coarser one's, which must be below 1 (the error shrinks).
void add_convergence(const CaseSpec& spec, const std::vector<RunResult>& runs, std::map<std::string, Metric>& metrics) {
  if (runs.size() < 2 || !spec.validation.contains("convergence")) return;
  const RunResult& fine = runs.back();
  const RunResult& coarse = runs[runs.size() - 2];
  for (const auto& name : spec.validation.at("convergence")) {
    const std::string n = name.get<std::string>();
    if (!fine.observed.metrics.count(n) || !coarse.observed.metrics.count(n)) continue;
    Metric ratio;
    ratio.value = fine.observed.metrics.at(n).value / coarse.observed.metrics.at(n).value;
    ratio.limit.max = 1.0;
    metrics[n + "_refinement_ratio"] = ratio;
  }
}

}  // namespace

json case_entry(const CaseSpec& spec, const std::string& tier, const std::vector<RunResult>& runs,
                const std::string& series_file, const std::vector<std::string>& plot_files) {
  const RunResult& fine = runs.back();
  std::map<std::string, Metric> metrics = fine.observed.metrics;
  add_convergence(spec, runs, metrics);
  std::string status = "pass", message;
  double wall = 0.0;
  json resolutions = json::array();
  for (const RunResult& r : runs) {
    wall += r.wall_seconds;
    if (r.status == "error") { status = "error"; message = r.message; }
    resolutions.push_back({{"spacing", r.spacing}, {"status", r.status}, {"particles", r.particles}, {"steps", r.steps},
                           {"wall_seconds", r.wall_seconds}, {"state_checksum", r.checksum},
                           {"metrics", metrics_json(r.observed.metrics)}});
  }
  if (status != "error")
    for (const auto& [name, m] : metrics)
      if (!m.pass()) status = "fail";
  json entry = {{"name", spec.name}, {"tier", tier}, {"status", status}, {"wall_seconds", wall},
                {"particles", fine.particles}, {"steps", fine.steps}, {"state_checksum", fine.checksum},
                {"metrics", metrics_json(metrics)}, {"series", series_file}, {"plots", plot_files},
                {"spacing", fine.spacing}, {"dimension", spec.dimension}, {"resolutions", resolutions}};
  if (!message.empty()) entry["message"] = message;
  return entry;
}

json error_entry(const std::string& name, const std::string& tier, const std::string& message) {
  return {{"name", name}, {"tier", tier}, {"status", "error"}, {"wall_seconds", 0.0}, {"particles", 0}, {"steps", 0},
          {"state_checksum", nullptr}, {"metrics", json::object()}, {"series", nullptr}, {"plots", json::array()},
          {"message", message}};
}

std::string git_commit() {
  const std::string cmd = std::string("git -C '") + SANDCASTLE_SOURCE_DIR + "' rev-parse HEAD 2>/dev/null";
  std::string out;
  if (FILE* p = ::popen(cmd.c_str(), "r")) {
    char buf[128];
    while (std::fgets(buf, sizeof buf, p)) out += buf;
    ::pclose(p);
  }
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out.empty() ? "unknown" : out;
}

json report_document(const std::vector<json>& cases) {
  int passed = 0, failed = 0, errors = 0;
  for (const json& c : cases) {
    const std::string s = c.at("status");
    (s == "pass" ? passed : s == "fail" ? failed : errors)++;
  }
  return {{"schema_version", 1}, {"git_commit", git_commit()}, {"threads", omp_get_max_threads()},
          {"compiler", SANDCASTLE_COMPILER}, {"flags", SANDCASTLE_FLAGS}, {"cases", cases},
          {"summary", {{"passed", passed}, {"failed", failed}, {"errors", errors}, {"baseline", baseline_counts(cases)}}}};
}

std::string summary_markdown(const json& report) {
  std::ostringstream o;
  const json& s = report.at("summary");
  o << "# sandcastle validation\n\ncommit `" << report.at("git_commit").get<std::string>() << "`, "
    << report.at("threads") << " threads, " << report.at("compiler").get<std::string>() << "\n\n"
    << "**" << s.at("passed") << " passed, " << s.at("failed") << " failed, " << s.at("errors") << " errors**\n\n"
    << "| case | tier | status | particles | steps | wall [s] | metrics |\n|---|---|---|---|---|---|---|\n";
  for (const json& c : report.at("cases")) {
    std::string metrics;
    for (const auto& [name, m] : c.at("metrics").items()) {
      char buf[160];
      const std::string value = m.at("value").is_null() ? "n/a" : format_number(m.at("value").get<double>());
      std::snprintf(buf, sizeof buf, "%s%s = %s (limit %s)%s", metrics.empty() ? "" : "; ", name.c_str(), value.c_str(),
                    m.at("limit").dump().c_str(), m.at("pass").get<bool>() ? "" : " **FAIL**");
      metrics += buf;
    }
    if (c.contains("message")) metrics += (metrics.empty() ? "" : "; ") + c.at("message").get<std::string>();
    char wall[32];
    std::snprintf(wall, sizeof wall, "%.1f", c.at("wall_seconds").get<double>());
    o << "| " << run_key(c) << " | " << c.at("tier").get<std::string>() << " | "
      << c.at("status").get<std::string>() << " | " << c.at("particles") << " | " << c.at("steps") << " | " << wall
      << " | " << metrics << " |\n";
  }
  return o.str();
}

std::string filmstrip_markdown(const json& report) {
  std::ostringstream o;
  for (const json& c : report.at("cases")) {
    if (c.contains("filmstrip"))
      o << "\n**" << run_key(c) << "**\n\n![" << run_key(c) << "](" << c.at("filmstrip").get<std::string>() << ")\n";
    else if (c.contains("filmstrip_note"))
      o << "\n**" << run_key(c) << "**: no filmstrip (" << c.at("filmstrip_note").get<std::string>() << ")\n";
  }
  const std::string strips = o.str();
  return strips.empty() ? strips : "\n## Filmstrips\n" + strips;
}

}  // namespace sc
