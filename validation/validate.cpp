// `sandcastle validate`: runs the cases of a tier, compares each with its reference and writes
// report.json, one series.json and PNG plots per case, and summary.md.
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include "baseline.hpp"
#include "data_root.hpp"
#include "errata.hpp"
#include "io/atomic_file.hpp"
#include "report.hpp"
#include "report_scripts.hpp"
#include "runner.hpp"
#include "scene/scene_builder.hpp"

namespace fs = std::filesystem;

namespace sc {

namespace {

/// Runs one case at every spacing of the tier and returns its report entry.
json validate_case(const CaseSpec& spec, const ValidateOptions& opt, int& exit_code) {
  const TierSpec& tier = spec.tiers.at(opt.tier);
  for (std::size_t k = 0; k < tier.spacings.size(); ++k)  // every spacing, before the first run
    check_particle_count(spec, tier.spacings[k], opt.max_particles, "/tiers/" + opt.tier + "/spacings/" + std::to_string(k));
  const std::string case_dir = opt.out_dir + "/" + spec.name;
  std::vector<RunResult> runs;
  for (std::size_t k = 0; k < tier.spacings.size(); ++k) {
    RunSettings settings;
    settings.out_dir = tier.spacings.size() == 1 ? case_dir : case_dir + "/dx" + std::to_string(k);
    settings.end_time = tier.end_time;
    settings.label = spec.name + (tier.spacings.size() > 1 ? " dx" + std::to_string(k) : "");
    runs.push_back(run_simulation(spec, tier.spacings[k], settings));
    if (runs.back().status == "error") break;
  }
  ObserverResult plotted = runs.back().observed;
  for (std::size_t k = 0; k + 1 < runs.size(); ++k)  // coarser resolutions join the plots
    for (const Series& s : runs[k].observed.series) {
      if (s.name.find("_sim") == std::string::npos) continue;
      Series renamed = s;
      renamed.name = s.name + "@dx" + format_number(runs[k].spacing);
      plotted.series.push_back(renamed);
      for (Plot& p : plotted.plots)
        for (std::size_t c = 0, n = p.curves.size(); c < n; ++c)
          if (p.curves[c].series == s.name)
            p.curves.push_back({renamed.name, p.curves[c].label + " dx = " + format_number(runs[k].spacing), "line"});
    }
  std::vector<std::string> plots;
  for (const Plot& p : plotted.plots) plots.push_back(spec.name + "/" + p.file);
  write_series_file(case_dir + "/series.json", spec.name, plotted);
  json entry = case_entry(spec, opt.tier, runs, spec.name + "/series.json", plots);
  add_baseline_comparison(spec, opt, entry, exit_code);
  const std::string status = entry.at("status");
  if (status == "error") exit_code = std::max(exit_code, static_cast<int>(runs.back().exit_code));
  else if (status == "fail" && exit_code == kSuccess) exit_code = kCaseFailed;
  return entry;
}

void run_plot_script(const std::string& out_dir) {
  const std::string cmd = std::string("/usr/bin/python3 '") + data_path("reports/plot_series.py") + "' '" + out_dir + "'";
  if (std::system(cmd.c_str()) != 0)
    std::cerr << "warning: plotting failed (needs python3-matplotlib); report.json and series are complete\n";
}

}  // namespace

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
  std::vector<json> entries;
  int exit_code = kSuccess;
  for (const std::string& file : files) {
    const std::string name = fs::path(file).parent_path().filename().string();
    try {
      const CaseSpec spec = load_case(file);
      if (!spec.tiers.count(opt.tier)) continue;  // a scene that is not part of this tier
      entries.push_back(validate_case(spec, opt, exit_code));
    } catch (const InputError& e) {
      std::cerr << "error: " << e.what() << "\n";
      entries.push_back(error_entry(name, opt.tier, e.what()));
      exit_code = kBadInput;
    }
    write_file_atomic(opt.out_dir + "/report.json", report_document(entries).dump(2) + "\n");
  }
  json report = report_document(entries);
  if (opt.errata) report["errata"] = run_errata(opt, cases_dir, entries);
  write_file_atomic(opt.out_dir + "/report.json", report.dump(2) + "\n");
  if (opt.plots) {
    run_plot_script(opt.out_dir);
    run_report_script("html_report.py", {opt.out_dir});  // report.html, with the plots embedded
  }
  const std::string summary = summary_markdown(report) + baseline_markdown(report) + errata_markdown(report);
  write_file_atomic(opt.out_dir + "/summary.md", summary);
  std::cout << summary;
  return exit_code;
}

}  // namespace sc
