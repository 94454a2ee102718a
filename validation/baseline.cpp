#include "baseline.hpp"

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <set>
#include <sstream>

#include "data_root.hpp"
#include "io/atomic_file.hpp"
#include "run_record.hpp"

namespace fs = std::filesystem;

namespace sc {

namespace {

/// Points kept per series in a baseline file (run_record.hpp, thinned): enough to resample a
/// time series, small enough for git.
constexpr std::size_t kBaselinePoints = 2000;

RunRecord record_from_baseline(const json& doc, const std::string& file) {
  try {
    RunRecord r;
    r.name = doc.at("case");
    r.tier = doc.at("tier");
    r.status = doc.at("status");
    r.checksum = doc.at("state_checksum");
    r.parameters_hash = doc.at("provenance").at("parameters_hash");
    r.spacing = doc.at("spacing");
    for (const auto& [name, value] : doc.at("metrics").items()) r.metrics[name] = value.is_number() ? value.get<double>() : NAN;
    r.series = series_from_json(doc.at("series"), file);
    return r;
  } catch (const json::exception& e) {
    throw InputError(file, "", std::string("not a baseline file: ") + e.what());
  }
}

/// A name in the case's "regression" limits that the run does not produce is a typo: bad input.
void check_limit_names(const CaseSpec& spec, const RunRecord& run) {
  std::set<std::string> series;
  for (const Series& s : run.series) series.insert(s.name);
  for (const auto& [name, limit] : spec.regression.series)
    if (!series.count(name)) throw InputError(spec.file, "/regression/series/" + name, "the case has no series of that name");
  for (const auto& [name, limit] : spec.regression.metrics)
    if (!run.metrics.count(name)) throw InputError(spec.file, "/regression/metrics/" + name, "the case has no metric of that name");
}

/// Series differences against the limits; failing names go to `failed`, `moved` is set when any
/// difference is non-zero.
json series_json(const RunRecord& base, const RunRecord& run, const RegressionSpec& limits,
                 std::vector<std::string>& failed, bool& moved) {
  json out = json::object();
  for (const Series& b : base.series) {
    const auto it = std::find_if(run.series.begin(), run.series.end(), [&](const Series& s) { return s.name == b.name; });
    const DifferenceLimit& limit = limits.for_series(b.name);
    if (it == run.series.end()) {
      out[b.name] = {{"note", "missing in this run"}, {"limit", limit.to_json()}, {"pass", false}};
      failed.push_back(b.name);
      moved = true;
      continue;
    }
    const SeriesDelta d = series_difference(b, *it);
    const bool pass = limit.accepts(d.relative_rms, d.max_difference);
    json item = {{"relative_rms", finite_or_null(d.relative_rms)}, {"max_difference", finite_or_null(d.max_difference)},
                 {"limit", limit.to_json()}, {"pass", pass}};
    if (!d.note.empty()) item["note"] = d.note;
    out[b.name] = item;
    if (!pass) failed.push_back(b.name);
    moved = moved || d.relative_rms != 0.0 || d.max_difference != 0.0;
  }
  for (const Series& s : run.series)
    if (!out.contains(s.name)) out[s.name] = {{"note", "not in the baseline"}, {"pass", true}};
  return out;
}

json metrics_json(const RunRecord& base, const RunRecord& run, const RegressionSpec& limits,
                  std::vector<std::string>& failed, bool& moved) {
  json out = json::object();
  for (const auto& [name, b] : base.metrics) {
    const DifferenceLimit& limit = limits.for_metric(name);
    const auto it = run.metrics.find(name);
    const double value = it == run.metrics.end() ? NAN : it->second;
    const MetricDelta d = it == run.metrics.end() ? MetricDelta{NAN, NAN} : metric_difference(b, value);
    const bool pass = limit.accepts(d.relative, std::abs(d.delta));
    out[name] = {{"baseline", finite_or_null(b)}, {"value", finite_or_null(value)}, {"delta", finite_or_null(d.delta)},
                 {"relative", finite_or_null(d.relative)}, {"limit", limit.to_json()}, {"pass", pass}};
    if (!pass) failed.push_back(name);
    moved = moved || d.delta != 0.0;
  }
  return out;
}

json missing(const std::string& file, const std::string& reason) {
  return {{"status", "missing"}, {"file", file}, {"reason", reason}};
}

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

std::string short_number(const json& v) { return v.is_number() ? format_number(v.get<double>()) : "n/a"; }

/// The items of a baseline comparison that moved, for summary.md.
std::string moved_items(const json& b) {
  std::string out;
  auto add = [&out](const std::string& text, const json& item) {
    out += (out.empty() ? "" : "; ") + text + " (limit " + item.value("limit", json::object()).dump() + ")" +
           (item.at("pass").get<bool>() ? "" : " **REGRESSED**");
  };
  for (const auto& [name, s] : b.at("series").items()) {
    if (s.contains("note")) add(name + ": " + s.at("note").get<std::string>(), s);
    else if (!s.at("max_difference").is_number() || s.at("max_difference").get<double>() != 0.0)
      add(name + " rel. RMS " + short_number(s.at("relative_rms")) + ", max " + short_number(s.at("max_difference")), s);
  }
  for (const auto& [name, m] : b.at("metrics").items())
    if (!m.at("delta").is_number() || m.at("delta").get<double>() != 0.0)
      add(name + " " + short_number(m.at("baseline")) + " -> " + short_number(m.at("value")), m);
  return out;
}

}  // namespace

std::string baselines_folder(const ValidateOptions& options) {
  return options.baselines_dir.empty() ? data_path("reference/baselines") : options.baselines_dir;
}

json build_identity() { return {{"compiler", SANDCASTLE_COMPILER}, {"flags", SANDCASTLE_FLAGS}}; }

json compare_with_baseline(const CaseSpec& spec, const json& entry, const std::string& run_dir,
                           const std::string& baselines_dir) {
  const RunRecord run = record_from_entry(entry, run_dir);
  check_limit_names(spec, run);
  const std::string id = run_key(entry);
  const std::string file = baselines_dir + "/" + id + ".json";
  if (!fs::exists(file))
    return missing(file, "no baseline; bless one with `sandcastle baseline --case " + spec.name +
                             (id == spec.name ? "" : " --method " + entry.at("method").get<std::string>()) + "`");
  const json doc = read_json_file(file);
  const RunRecord base = record_from_baseline(doc, file);
  if (base.tier != run.tier || base.spacing != run.spacing)
    return missing(file, "the baseline is for tier " + base.tier + " at spacing " + format_number(base.spacing));
  std::vector<std::string> failed;
  bool moved = base.checksum != run.checksum;
  json out = {{"file", file}, {"state_checksum", base.checksum}, {"provenance", doc.at("provenance")},
              {"same_build", doc.at("provenance").value("compiler", "") == SANDCASTLE_COMPILER &&
                                 doc.at("provenance").value("flags", "") == SANDCASTLE_FLAGS},
              {"parameters_changed", base.parameters_hash != spec.parameters_hash}};
  out["series"] = series_json(base, run, spec.regression, failed, moved);
  out["metrics"] = metrics_json(base, run, spec.regression, failed, moved);
  out["failed"] = failed;
  out["status"] = !failed.empty() ? "regressed" : moved ? "changed" : "identical";
  return out;
}

void add_baseline_comparison(const CaseSpec& spec, const ValidateOptions& options, json& entry, int& exit_code) {
  entry["parameters_hash"] = spec.parameters_hash;
  if (entry.at("status") == "error") {
    entry["baseline"] = {{"status", "not_compared"}, {"reason", "the run stopped with an error"}};
    return;
  }
  entry["baseline"] = compare_with_baseline(spec, entry, options.out_dir, baselines_folder(options));
  if (entry["baseline"]["status"] == "regressed" && exit_code == kSuccess) exit_code = kCaseFailed;
}

json baseline_document(const json& report, const json& entry, const std::string& run_dir, const std::string& date) {
  const RunRecord r = record_from_entry(entry, run_dir);
  json metrics = json::object(), series = json::array();
  for (const auto& [name, value] : r.metrics) metrics[name] = finite_or_null(value);
  for (const Series& full : r.series) {
    const Series s = thinned(full, kBaselinePoints);
    series.push_back({{"name", s.name}, {"x_label", s.x_label}, {"y_label", s.y_label}, {"x", s.x}, {"y", s.y}});
  }
  const json provenance = {{"commit", report.at("git_commit")}, {"date", date}, {"parameters_hash", r.parameters_hash},
                           {"threads", report.at("threads")}, {"compiler", report.at("compiler")},
                           {"flags", report.value("flags", "")}};
  return {{"format", "sandcastle baseline"}, {"version", 1}, {"case", r.name}, {"tier", r.tier},
          {"spacing", r.spacing}, {"particles", entry.at("particles")}, {"steps", entry.at("steps")},
          {"status", r.status}, {"state_checksum", r.checksum}, {"provenance", provenance},
          {"metrics", metrics}, {"series", series}};
}

int write_baselines(const std::string& run_dir, const std::string& baselines_dir, const std::vector<std::string>& names,
                    const std::vector<std::string>& methods) {
  const json report = read_json_file(run_dir + "/report.json");
  const std::string date = utc_now();
  int exit_code = kSuccess;
  const std::set<std::string> wanted(names.begin(), names.end());
  std::set<std::string> found;
  const bool all_methods = methods == std::vector<std::string>{"all"};
  fs::create_directories(baselines_dir);
  for (const json& entry : report.at("cases")) {
    const std::string name = entry.at("name"), id = run_key(entry);
    if (!wanted.empty() && !wanted.count(name)) continue;
    const bool method_wanted = all_methods || (methods.empty() ? id == name
                                                               : std::count(methods.begin(), methods.end(), entry.value("method", "")) > 0);
    if (!method_wanted) continue;
    found.insert(name);
    if (entry.at("status") == "error") {
      std::cerr << "error: " << id << " stopped with an error; no baseline written\n";
      exit_code = kBadInput;
      continue;
    }
    if (entry.at("status") == "fail") std::cerr << "warning: " << id << " fails its physics gate; blessing it anyway\n";
    const std::string file = baselines_dir + "/" + id + ".json";
    write_file_atomic(file, baseline_document(report, entry, run_dir, date).dump(1) + "\n");
    std::cout << "baseline " << file << " (checksum " << entry.at("state_checksum").get<std::string>() << ")\n";
  }
  for (const std::string& name : wanted)
    if (!found.count(name)) {
      std::cerr << "error: no run of case '" << name << "' by the methods asked in " << run_dir << "/report.json\n";
      exit_code = kBadInput;
    }
  return exit_code;
}

json baseline_counts(const std::vector<json>& cases) {
  json counts = {{"identical", 0}, {"changed", 0}, {"regressed", 0}, {"missing", 0}, {"not_compared", 0}};
  for (const json& c : cases) {
    if (!c.contains("baseline")) continue;
    json& n = counts[c.at("baseline").at("status").get<std::string>()];
    n = n.get<int>() + 1;
  }
  return counts;
}

std::string baseline_markdown(const json& report) {
  std::ostringstream o;
  o << "\n## Baselines\n\n| case | baseline | what moved |\n|---|---|---|\n";
  for (const json& c : report.at("cases")) {
    if (!c.contains("baseline")) continue;
    const json& b = c.at("baseline");
    const std::string status = b.at("status");
    std::string detail = b.contains("reason") ? b.at("reason").get<std::string>() : "";
    if (status == "changed" || status == "regressed") detail = moved_items(b);
    if (status == "identical") detail = "checksum " + b.at("state_checksum").get<std::string>();
    o << "| " << run_key(c) << " | " << (status == "regressed" ? "**regressed**" : status) << " | "
      << detail << " |\n";
  }
  return o.str();
}

}  // namespace sc
