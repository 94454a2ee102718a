// `sandcastle validate`: runs the cases of a tier, compares each with its reference and writes
// report.json, one series.json and PNG plots per case, and summary.md.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include "baseline.hpp"
#include "convergence.hpp"
#include "data_root.hpp"
#include "errata.hpp"
#include "io/atomic_file.hpp"
#include "method/registry.hpp"
#include "methods_report.hpp"
#include "render/render.hpp"
#include "report.hpp"
#include "report_scripts.hpp"
#include "runner.hpp"
#include "scene/scene_builder.hpp"
#include "sweep.hpp"

namespace fs = std::filesystem;

namespace sc {

namespace {

/// The case's filmstrip in the report: `render` draws the frames of the finest run (run_dir) that
/// the filmstrip takes (the case's render.filmstrip, else the first, middle and last) into
/// <id>/pictures/ and the entry gets "filmstrip", its path in the report. Returns why there is none
/// when drawing fails, else empty: a picture never changes a case's status.
std::string add_filmstrip(const CaseSpec& spec, const std::string& id, const std::string& run_dir,
                          const ValidateOptions& opt, json& entry) {
  render::RenderOptions o;
  o.run_dir = run_dir;
  o.out_dir = opt.out_dir + "/" + id + "/pictures";
  o.case_file = spec.file;
  o.filmstrip = o.strip_only = true;
  try {
    if (render::render_run(o) != kSuccess) return "drawing failed (its log is in " + o.out_dir + ")";
  } catch (const std::exception& e) {
    return e.what();
  }
  entry["filmstrip"] = id + "/pictures/filmstrip.png";
  return "";
}

/// Runs one case by one method (spec.method) at every spacing of the tier: its report entry, and
/// what the finest run observed (for the side-by-side comparison of methods). With pictures, the
/// finest run writes its frames (3-D: and surfaces) and the entry gets its filmstrip, or a note
/// saying why there is none.
MethodRun validate_case(const CaseSpec& spec, const std::string& id, const ValidateOptions& opt, int& exit_code) {
  const TierSpec& tier = spec.tiers.at(opt.tier);
  const std::string case_dir = opt.out_dir + "/" + id;
  const bool pictures = opt.plots && opt.pictures;
  const std::string missing = pictures ? render::missing_programs(spec.dimension, true) : "";
  std::vector<RunResult> runs;
  std::string finest_dir;
  for (std::size_t k = 0; k < tier.spacings.size(); ++k) {
    RunSettings settings;
    settings.out_dir = tier.spacings.size() == 1 ? case_dir : case_dir + "/dx" + std::to_string(k);
    settings.end_time = tier.end_time;
    settings.label = id + (tier.spacings.size() > 1 ? " dx" + std::to_string(k) : "");
    settings.write_frames = pictures && missing.empty() && k + 1 == tier.spacings.size();
    settings.write_surfaces = settings.write_frames && spec.dimension == 3;
    finest_dir = settings.out_dir;
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
  std::string no_filmstrip = missing;
  if (pictures && missing.empty() && runs.size() == tier.spacings.size())
    no_filmstrip = add_filmstrip(spec, id, finest_dir, opt, entry);
  if (!no_filmstrip.empty()) {
    std::cerr << "note: " << id << ": no filmstrip: " << no_filmstrip << "\n";
    entry["filmstrip_note"] = no_filmstrip;
  }
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

/// The case files of the run: every case of the folder, or those named with --case (in that order).
std::vector<std::string> case_files(const std::string& cases_dir, const ValidateOptions& opt) {
  if (opt.cases.empty()) return discover_cases(cases_dir);
  std::vector<std::string> chosen;
  for (const std::string& name : opt.cases) {
    const std::string file = cases_dir + "/" + name + "/case.json";
    if (!fs::exists(file)) throw InputError(file, "", "no case named '" + name + "' (see " + cases_dir + ")");
    chosen.push_back(file);
  }
  return chosen;
}

/// The expected work of a case in the tier, for handing out the longest first: particles times
/// steps at the largest step, summed over its spacings and methods (0 for a case that does not load
/// or is not in the tier: it ends at once).
double expected_cost(const std::string& file, const ValidateOptions& opt) {
  try {
    const CaseSpec spec = load_case(file);
    const auto tier = spec.tiers.find(opt.tier);
    if (tier == spec.tiers.end()) return 0.0;
    const double end = tier->second.end_time > 0.0 ? tier->second.end_time : spec.end_time;
    double cost = 0.0;
    for (const double dx : tier->second.spacings) cost += estimate_particles(spec, dx) * end / spec.dt_max;
    return cost * static_cast<double>(methods_to_run(spec, opt).size());
  } catch (const std::exception&) {
    return 0.0;
  }
}

/// One case of the sweep, run by every method asked of it: its report entries, its methods
/// comparison and the exit code it asks for, as JSON text. Whatever goes wrong (bad input, an
/// unexpected error) becomes the case's error entry: a sweep never loses a case.
std::string validate_file(const std::string& file, const ValidateOptions& opt) {
  const std::string name = fs::path(file).parent_path().filename().string();
  std::vector<json> entries, comparisons;
  int exit_code = kSuccess;
  try {
    const CaseSpec spec = load_case(file);
    if (spec.tiers.count(opt.tier)) validate_methods(spec, opt, entries, comparisons, exit_code);  // else not in this tier
  } catch (const InputError& e) {
    std::cerr << "error: " << e.what() << "\n";
    entries.push_back(error_entry(name, opt.tier, e.what()));
    exit_code = std::max(exit_code, static_cast<int>(kBadInput));
  } catch (const std::exception& e) {
    std::cerr << "error: " << name << ": " << e.what() << "\n";
    entries.push_back(error_entry(name, opt.tier, e.what()));
    exit_code = std::max(exit_code, static_cast<int>(kInternalError));
  }
  return json{{"entries", entries}, {"comparisons", comparisons}, {"exit_code", exit_code}}.dump();
}

/// The cases of a tier as a sweep: each case file one task; on rank 0 their entries, comparisons
/// and exit code in file order, report.json rewritten as cases finish. False on the other ranks.
bool sweep_cases(const std::vector<std::string>& files, const ValidateOptions& opt, std::vector<json>& entries,
                 std::vector<json>& comparisons, int& exit_code) {
  std::vector<double> costs;
  for (const std::string& file : files) costs.push_back(expected_cost(file, opt));
  const auto collect = [&](const std::vector<std::string>& results) {
    entries.clear();
    comparisons.clear();
    exit_code = kSuccess;
    for (const std::string& text : results) {
      if (text.empty()) continue;  // not known yet on this rank
      const json r = json::parse(text);
      for (const json& e : r.at("entries")) entries.push_back(e);
      for (const json& c : r.at("comparisons")) comparisons.push_back(c);
      exit_code = std::max(exit_code, r.at("exit_code").get<int>());
    }
  };
  const std::vector<std::string> results = sweep(
      costs, [&](std::size_t i) { return validate_file(files[i], opt); },
      [&](const std::vector<std::string>& known) {  // the report so far, as cases finish
        collect(known);
        write_file_atomic(opt.out_dir + "/report.json", report_document(entries).dump(2) + "\n");
      });
  if (sweep_rank() != 0) return false;
  collect(results);
  return true;
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
  const std::vector<std::string> files = case_files(cases_dir, opt);
  if (sweep_rank() == 0) fs::create_directories(opt.out_dir);
  int exit_code = kSuccess;
  json report;
  if (opt.convergence) {
    const json studies = run_convergence(files, opt, exit_code);
    if (sweep_rank() != 0) return broadcast_from_root(kSuccess);
    broadcast_from_root(exit_code);
    report = report_document({});
    report["convergence"] = studies;
  } else {
    std::vector<json> entries, comparisons;
    if (!sweep_cases(files, opt, entries, comparisons, exit_code)) return broadcast_from_root(kSuccess);
    broadcast_from_root(exit_code);
    report = report_document(entries);
    if (!opt.methods.empty()) report["methods"] = comparisons;
    if (opt.errata) report["errata"] = run_errata(opt, cases_dir, entries);
  }
  write_file_atomic(opt.out_dir + "/report.json", report.dump(2) + "\n");
  if (opt.plots) {
    run_plot_script(opt.out_dir);
    run_report_script("html_report.py", {opt.out_dir});  // report.html, with the plots embedded
  }
  const std::string summary = summary_markdown(report) + methods_markdown(report) + baseline_markdown(report) +
                              errata_markdown(report) + convergence_markdown(report) + filmstrip_markdown(report);
  write_file_atomic(opt.out_dir + "/summary.md", summary);
  std::cout << summary;
  return exit_code;
}

}  // namespace sc
