#include "compare.hpp"

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "io/atomic_file.hpp"
#include "report_scripts.hpp"
#include "run_record.hpp"

namespace fs = std::filesystem;

namespace sc {

namespace {

json run_header(const std::string& dir, const json& report) {
  return {{"dir", fs::absolute(dir).lexically_normal().string()}, {"git_commit", report.at("git_commit")},
          {"threads", report.at("threads")}, {"compiler", report.at("compiler")}, {"flags", report.value("flags", "")}};
}

const json* find_case(const json& report, const std::string& key) {
  for (const json& c : report.at("cases"))
    if (run_key(c) == key) return &c;
  return nullptr;
}

json metrics_delta(const RunRecord& a, const RunRecord& b) {
  json out = json::object();
  for (const auto& [name, va] : a.metrics) {
    const auto it = b.metrics.find(name);
    const double vb = it == b.metrics.end() ? NAN : it->second;
    const MetricDelta d = metric_difference(va, vb);
    out[name] = {{"a", finite_or_null(va)}, {"b", finite_or_null(vb)}, {"delta", finite_or_null(d.delta)},
                 {"relative", finite_or_null(d.relative)}};
  }
  for (const auto& [name, vb] : b.metrics)
    if (!out.contains(name)) out[name] = {{"a", nullptr}, {"b", finite_or_null(vb)}, {"delta", nullptr}, {"relative", nullptr}};
  return out;
}

json series_delta(const RunRecord& a, const RunRecord& b) {
  json out = json::object();
  for (const Series& sa : a.series) {
    const auto it = std::find_if(b.series.begin(), b.series.end(), [&](const Series& s) { return s.name == sa.name; });
    if (it == b.series.end()) {
      out[sa.name] = {{"note", "only in run A"}};
      continue;
    }
    const SeriesDelta d = series_difference(sa, *it);
    out[sa.name] = {{"relative_rms", finite_or_null(d.relative_rms)}, {"max_difference", finite_or_null(d.max_difference)}};
    if (!d.note.empty()) out[sa.name]["note"] = d.note;
  }
  for (const Series& sb : b.series)
    if (!out.contains(sb.name)) out[sb.name] = {{"note", "only in run B"}};
  return out;
}

json case_delta(const json& entry_a, const std::string& dir_a, const json& entry_b, const std::string& dir_b) {
  const RunRecord a = record_from_entry(entry_a, dir_a), b = record_from_entry(entry_b, dir_b);
  auto path = [](const std::string& dir, const json& e) {
    return e.at("series").is_string() ? json((fs::absolute(dir) / e.at("series").get<std::string>()).lexically_normal().string())
                                      : json(nullptr);
  };
  return {{"name", run_key(entry_a)}, {"status", {{"a", a.status}, {"b", b.status}}},
          {"state_checksum", {{"a", a.checksum}, {"b", b.checksum}}},
          {"identical", !a.checksum.empty() && a.checksum == b.checksum},
          {"metrics", metrics_delta(a, b)}, {"series", series_delta(a, b)},
          {"series_file", {{"a", path(dir_a, entry_a)}, {"b", path(dir_b, entry_b)}}}};
}

std::string cell(const json& v) {
  if (v.is_number()) return format_number(v.get<double>());
  return v.is_string() ? v.get<std::string>() : "n/a";
}

}  // namespace

json compare_document(const std::string& run_a, const std::string& run_b) {
  const json ra = read_json_file(run_a + "/report.json"), rb = read_json_file(run_b + "/report.json");
  json cases = json::array(), only_a = json::array(), only_b = json::array();
  for (const json& ea : ra.at("cases")) {
    const json* eb = find_case(rb, run_key(ea));
    if (eb) cases.push_back(case_delta(ea, run_a, *eb, run_b));
    else only_a.push_back(run_key(ea));
  }
  for (const json& eb : rb.at("cases"))
    if (!find_case(ra, run_key(eb))) only_b.push_back(run_key(eb));
  return {{"format", "sandcastle compare"}, {"version", 1}, {"run_a", run_header(run_a, ra)}, {"run_b", run_header(run_b, rb)},
          {"cases", cases}, {"only_in_a", only_a}, {"only_in_b", only_b}};
}

std::string compare_markdown(const json& doc) {
  std::ostringstream o;
  o << "# sandcastle compare\n\nA: `" << doc.at("run_a").at("dir").get<std::string>() << "` (commit "
    << doc.at("run_a").at("git_commit").get<std::string>() << ")\nB: `" << doc.at("run_b").at("dir").get<std::string>()
    << "` (commit " << doc.at("run_b").at("git_commit").get<std::string>() << ")\n";
  for (const json& c : doc.at("cases")) {
    o << "\n## " << c.at("name").get<std::string>() << ": "
      << (c.at("identical").get<bool>() ? "identical" : "changed") << " (status " << c.at("status").at("a").get<std::string>()
      << " -> " << c.at("status").at("b").get<std::string>() << ", checksum " << cell(c.at("state_checksum").at("a"))
      << " -> " << cell(c.at("state_checksum").at("b")) << ")\n\n| metric | A | B | delta | relative |\n|---|---|---|---|---|\n";
    for (const auto& [name, m] : c.at("metrics").items())
      o << "| " << name << " | " << cell(m.at("a")) << " | " << cell(m.at("b")) << " | " << cell(m.at("delta")) << " | "
        << cell(m.at("relative")) << " |\n";
    o << "\n| series | relative RMS | max difference |\n|---|---|---|\n";
    for (const auto& [name, s] : c.at("series").items())
      o << "| " << name << " | " << (s.contains("note") ? s.at("note").get<std::string>() : cell(s.at("relative_rms")))
        << " | " << (s.contains("max_difference") ? cell(s.at("max_difference")) : "") << " |\n";
  }
  for (const char* side : {"only_in_a", "only_in_b"})
    if (!doc.at(side).empty()) o << "\n" << side << ": " << doc.at(side).dump() << "\n";
  return o.str();
}

int compare_runs(const std::string& run_a, const std::string& run_b, const std::string& out_dir, bool plots) {
  const json doc = compare_document(run_a, run_b);
  fs::create_directories(out_dir);
  write_file_atomic(out_dir + "/compare.json", doc.dump(2) + "\n");
  const std::string md = compare_markdown(doc);
  write_file_atomic(out_dir + "/compare.md", md);
  if (plots) run_report_script("compare_report.py", {out_dir});
  std::cout << md;
  return 0;
}

}  // namespace sc
