// `sandcastle validate`: runs the cases of a tier, compares each with its reference and writes
// report.json, one series.json and PNG plots per case, and summary.md.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include "baseline.hpp"
#include "data_root.hpp"
#include "errata.hpp"
#include "io/atomic_file.hpp"
#include "method/registry.hpp"
#include "methods_report.hpp"
#include "report.hpp"
#include "report_scripts.hpp"
#include "runner.hpp"
#include "scene/scene_builder.hpp"

namespace fs = std::filesystem;

namespace sc {

namespace {

/// Runs one case by one method (spec.method) at every spacing of the tier: its report entry, and
/// what the finest run observed (for the side-by-side comparison of methods).
MethodRun validate_case(const CaseSpec& spec, const std::string& id, const ValidateOptions& opt, int& exit_code) {
  const TierSpec& tier = spec.tiers.at(opt.tier);
  const std::string case_dir = opt.out_dir + "/" + id;
  std::vector<RunResult> runs;
  for (std::size_t k = 0; k < tier.spacings.size(); ++k) {
    RunSettings settings;
    settings.out_dir = tier.spacings.size() == 1 ? case_dir : case_dir + "/dx" + std::to_string(k);
    settings.end_time = tier.end_time;
    settings.label = id + (tier.spacings.size() > 1 ? " dx" + std::to_string(k) : "");
    runs.push_back(run_simulation(spec, tier.spacings[k], settings));
    if (runs.back().status == "error") break;
  }
  ObserverResult plotted = runs.back().observed;
  for (std::size_t k = 0; k + 1 < runs.size(); ++k)  // coarser resolutions join the plots
    for (const Series& s : runs[k].observed.series) {
      if (!is_simulated(s)) continue;
      Series renamed = s;
      renamed.name = s.name + "@dx" + format_number(runs[k].spacing);
      plotted.series.push_back(renamed);
      for (Plot& p : plotted.plots)
        for (std::size_t c = 0, n = p.curves.size(); c < n; ++c)
          if (p.curves[c].series == s.name)
            p.curves.push_back({renamed.name, p.curves[c].label + " dx = " + format_number(runs[k].spacing), "line"});
    }
  std::vector<std::string> plots;
  for (const Plot& p : plotted.plots) plots.push_back(id + "/" + p.file);
  write_series_file(case_dir + "/series.json", spec.name, plotted);
  json entry = case_entry(spec, opt.tier, runs, id + "/series.json", plots);
  entry["method"] = spec.method;
  entry["run_id"] = id;
  add_baseline_comparison(spec, opt, entry, exit_code);
  const std::string status = entry.at("status");
  if (status == "error") exit_code = std::max(exit_code, static_cast<int>(runs.back().exit_code));
  else if (status == "fail" && exit_code == kSuccess) exit_code = kCaseFailed;
  return {spec.method, entry, runs.back().observed};
}

/// Runs one case with every method asked of it; adds their entries to `entries` and, when more
/// than one method ran, their side-by-side comparison to `comparisons`.
void validate_methods(const CaseSpec& spec, const ValidateOptions& opt, std::vector<json>& entries,
                      std::vector<json>& comparisons, int& exit_code) {
  const std::vector<std::string> methods = methods_to_run(spec, opt);
  if (methods.empty()) {
    const std::string rule = "the case supports none of the methods asked with --method (it supports \"" +
                             spec.method + "\" and the keys of \"methods\")";
    if (!opt.cases.empty()) throw InputError(spec.file, "/methods", rule);  // named with --case: a mistake
    std::cerr << "note: " << spec.name << " skipped: " << rule << "\n";
    return;
  }
  std::vector<CaseSpec> specs;
  for (const std::string& m : methods) specs.push_back(with_method(spec, m));
  const TierSpec& tier = spec.tiers.at(opt.tier);
  for (const CaseSpec& s : specs)  // every method and spacing, before the first run
    for (std::size_t k = 0; k < tier.spacings.size(); ++k)
      check_particle_count(s, tier.spacings[k], opt.max_particles, "/tiers/" + opt.tier + "/spacings/" + std::to_string(k));
  std::vector<MethodRun> runs;
  for (const CaseSpec& s : specs) {
    runs.push_back(validate_case(s, run_id(spec, s.method), opt, exit_code));
    entries.push_back(runs.back().entry);
  }
  if (runs.size() > 1) comparisons.push_back(methods_comparison(spec, runs, opt.out_dir));
}

void run_plot_script(const std::string& out_dir) {
  const std::string cmd = std::string("/usr/bin/python3 '") + data_path("reports/plot_series.py") + "' '" + out_dir + "'";
  if (std::system(cmd.c_str()) != 0)
    std::cerr << "warning: plotting failed (needs python3-matplotlib); report.json and series are complete\n";
}

}  // namespace

std::vector<std::string> methods_to_run(const CaseSpec& spec, const ValidateOptions& options) {
  if (options.methods.empty()) return {spec.method};
  std::vector<std::string> asked = options.methods;
  if (asked == std::vector<std::string>{"all"}) {
    const auto tier = spec.tiers.find(options.tier);
    if (tier != spec.tiers.end() && !tier->second.methods.empty()) return tier->second.methods;
    asked = {spec.method};
    for (const auto& [name, params] : spec.methods.items()) asked.push_back(name);
  }
  std::vector<std::string> out;
  for (const std::string& m : asked)
    if (spec.supports(m) && std::find(out.begin(), out.end(), m) == out.end()) out.push_back(m);
  return out;
}

std::string run_id(const CaseSpec& spec, const std::string& method) {
  return method == spec.method ? spec.name : spec.name + "." + method;
}

int validate(const ValidateOptions& opt) {
  const std::string cases_dir = opt.cases_dir.empty() ? data_path("cases") : opt.cases_dir;
  std::vector<std::string> files = discover_cases(cases_dir);
  if (!opt.cases.empty()) {
    std::vector<std::string> chosen;
    for (const std::string& name : opt.cases) {
      const std::string file = cases_dir + "/" + name + "/case.json";
      if (!fs::exists(file)) throw InputError(file, "", "no case named '" + name + "' (see " + cases_dir + ")");
      chosen.push_back(file);
    }
    files = chosen;
  }
  fs::create_directories(opt.out_dir);
  std::vector<json> entries, comparisons;
  int exit_code = kSuccess;
  for (const std::string& file : files) {
    const std::string name = fs::path(file).parent_path().filename().string();
    try {
      const CaseSpec spec = load_case(file);
      if (!spec.tiers.count(opt.tier)) continue;  // a scene that is not part of this tier
      validate_methods(spec, opt, entries, comparisons, exit_code);
    } catch (const InputError& e) {
      std::cerr << "error: " << e.what() << "\n";
      entries.push_back(error_entry(name, opt.tier, e.what()));
      exit_code = kBadInput;
    }
    write_file_atomic(opt.out_dir + "/report.json", report_document(entries).dump(2) + "\n");
  }
  json report = report_document(entries);
  if (!opt.methods.empty()) report["methods"] = comparisons;
  if (opt.errata) report["errata"] = run_errata(opt, cases_dir, entries);
  write_file_atomic(opt.out_dir + "/report.json", report.dump(2) + "\n");
  if (opt.plots) {
    run_plot_script(opt.out_dir);
    run_report_script("html_report.py", {opt.out_dir});  // report.html, with the plots embedded
  }
  const std::string summary =
      summary_markdown(report) + methods_markdown(report) + baseline_markdown(report) + errata_markdown(report);
  write_file_atomic(opt.out_dir + "/summary.md", summary);
  std::cout << summary;
  return exit_code;
}

}  // namespace sc
