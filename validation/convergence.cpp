#include "convergence.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <sstream>

#include "io/atomic_file.hpp"
#include "method/registry.hpp"
#include "scene/scene_builder.hpp"
#include "sweep.hpp"

namespace sc {

namespace {

/// One case by one method, at the spacings of its study.
struct Study {
  CaseSpec spec;  ///< with_method of the method
  std::string method, id;
  const std::vector<double>& spacings() const { return spec.convergence->spacings; }
};

/// The run of a study at its k-th spacing.
struct Task {
  std::size_t study, k;
};

/// The studies of the cases in `files`, each case by every method asked of it; a case named with
/// --case must have a study. Every run's particle count is checked before any run starts.
std::vector<Study> studies_of(const std::vector<std::string>& files, const ValidateOptions& opt) {
  std::vector<Study> out;
  for (const std::string& file : files) {
    const CaseSpec spec = load_case(file);
    if (!spec.convergence) {
      if (!opt.cases.empty()) throw InputError(file, "/convergence", "the case has no convergence study to run");
      continue;
    }
    for (const std::string& method : methods_to_run(spec, opt)) {
      Study s{with_method(spec, method), method, run_id(spec, method)};
      for (std::size_t k = 0; k < s.spacings().size(); ++k)
        check_particle_count(s.spec, s.spacings()[k], opt.max_particles, "/convergence/spacings/" + std::to_string(k));
      out.push_back(std::move(s));
    }
  }
  return out;
}

/// The run's end: the full tier's end time where it sets one (a study is as long as the full run),
/// else the case's.
double study_end_time(const CaseSpec& spec) {
  const auto full = spec.tiers.find("full");
  return full != spec.tiers.end() ? full->second.end_time : 0.0;
}

std::string study_dir(const ValidateOptions& opt, const Study& s) { return opt.out_dir + "/convergence/" + s.id; }

/// One run of a study as JSON text: status, message, exit code, particles, wall time and every
/// metric's value. Whatever goes wrong becomes the run's error.
std::string run_task(const Study& s, std::size_t k, const ValidateOptions& opt) {
  const double dx = s.spacings()[k];
  RunSettings settings;
  settings.out_dir = study_dir(opt, s) + "/dx" + std::to_string(k);
  settings.end_time = study_end_time(s.spec);
  settings.label = s.id + " dx " + format_number(dx);
  try {
    const RunResult r = run_simulation(s.spec, dx, settings);
    json metrics = json::object();
    for (const auto& [name, m] : r.observed.metrics) metrics[name] = m.value;
    return json{{"spacing", dx},         {"status", r.status},
                {"message", r.message},  {"exit_code", r.exit_code},
                {"particles", r.particles}, {"wall_seconds", r.wall_seconds},
                {"metrics", metrics}}.dump();
  } catch (const std::exception& e) {
    std::cerr << "error: " << settings.label << ": " << e.what() << "\n";
    const int code = dynamic_cast<const InputError*>(&e) ? kBadInput : kInternalError;
    return json{{"spacing", dx}, {"status", "error"}, {"message", e.what()}, {"exit_code", code},
                {"metrics", json::object()}}.dump();
  }
}

/// A study's entry of the report from its runs (coarse to fine), and its series.json.
json study_entry(const Study& s, const std::vector<json>& runs, const ValidateOptions& opt, int& exit_code) {
  json entry{{"case", s.spec.name}, {"method", s.method}, {"run_id", s.id}, {"spacings", s.spacings()},
             {"status", "ok"},      {"metrics", json::object()}, {"plots", json::array()}};
  json run_list = json::array();
  for (const json& r : runs) {
    json brief = r;
    brief.erase("metrics");
    run_list.push_back(brief);
    if (r.at("status") == "error") {
      entry["status"] = "error";
      exit_code = std::max(exit_code, r.at("exit_code").get<int>());
    }
  }
  entry["runs"] = run_list;
  ObserverResult plotted;
  for (const auto& [name, order] : s.spec.convergence->orders) {
    std::vector<double> errors;
    for (const json& r : runs) {  // a metric the run lacks, or NaN (written as null), has no error
      const json& metrics = r.at("metrics");
      const bool known = metrics.contains(name) && metrics.at(name).is_number();
      errors.push_back(known ? metrics.at(name).get<double>() : std::numeric_limits<double>::quiet_NaN());
    }
    const double observed = observed_order(s.spacings(), errors);
    json m{{"errors", json::array()}, {"expected_order", order}, {"observed_order", nullptr}};
    for (const double e : errors) m["errors"].push_back(std::isfinite(e) ? json(e) : json(nullptr));
    if (std::isfinite(observed)) m["observed_order"] = observed;
    entry["metrics"][name] = m;
    Series measured{name, "spacing dx [m]", name, {}, {}}, expected{name + "_expected", "spacing dx [m]", name, {}, {}};
    for (std::size_t k = 0; k < errors.size(); ++k)
      if (std::isfinite(errors[k]) && errors[k] > 0.0) measured.x.push_back(s.spacings()[k]), measured.y.push_back(errors[k]);
    if (measured.x.empty()) continue;
    for (const double dx : s.spacings()) {  // the expected order through the finest measured point
      expected.x.push_back(dx);
      expected.y.push_back(measured.y.back() * std::pow(dx / measured.x.back(), order));
    }
    const std::string file = name + "_convergence.png";
    plotted.plots.push_back({file, s.id + ": " + name + " against the spacing", "spacing dx [m]", name,
                             {{name, "measured (order " + format_number(observed) + ")", "markers"},
                              {expected.name, "order " + format_number(order), "line"}},
                             true});
    plotted.series.push_back(measured);
    plotted.series.push_back(expected);
    entry["plots"].push_back("convergence/" + s.id + "/" + file);
  }
  write_series_file(study_dir(opt, s) + "/series.json", s.spec.name, plotted);
  entry["series"] = "convergence/" + s.id + "/series.json";
  return entry;
}

}  // namespace

double observed_order(const std::vector<double>& spacings, const std::vector<double>& errors) {
  double n = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
  for (std::size_t k = 0; k < std::min(spacings.size(), errors.size()); ++k) {
    if (!(std::isfinite(errors[k]) && errors[k] > 0.0 && spacings[k] > 0.0)) continue;
    const double x = std::log(spacings[k]), y = std::log(errors[k]);
    n += 1.0, sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  const double det = n * sxx - sx * sx;
  if (n < 2.0 || !(det > 1e-12 * n * n)) return std::numeric_limits<double>::quiet_NaN();
  return (n * sxy - sx * sy) / det;
}

json run_convergence(const std::vector<std::string>& files, const ValidateOptions& opt, int& exit_code) {
  const std::vector<Study> studies = studies_of(files, opt);
  std::vector<Task> tasks;
  std::vector<double> costs;
  for (std::size_t i = 0; i < studies.size(); ++i)
    for (std::size_t k = 0; k < studies[i].spacings().size(); ++k) {
      tasks.push_back({i, k});
      const CaseSpec& spec = studies[i].spec;
      const double end = study_end_time(spec) > 0.0 ? study_end_time(spec) : spec.end_time;
      costs.push_back(estimate_particles(spec, studies[i].spacings()[k]) * end / spec.dt_max);
    }
  const std::vector<std::string> results = sweep(
      costs, [&](std::size_t t) { return run_task(studies[tasks[t].study], tasks[t].k, opt); });
  if (sweep_rank() != 0) return nullptr;
  json entries = json::array();
  std::size_t t = 0;
  for (const Study& s : studies) {
    std::vector<json> runs;
    for (std::size_t k = 0; k < s.spacings().size(); ++k) runs.push_back(json::parse(results[t++]));
    entries.push_back(study_entry(s, runs, opt, exit_code));
  }
  return entries;
}

std::string convergence_markdown(const json& report) {
  if (!report.contains("convergence")) return "";
  std::ostringstream o;
  o << "\n## Convergence (error against the spacing; observed order = least-squares slope in log-log)\n\n"
    << "| case | method | metric | spacings | errors | observed order | expected order |\n|---|---|---|---|---|---|---|\n";
  for (const json& s : report.at("convergence")) {
    std::string spacings;
    for (const json& dx : s.at("spacings")) spacings += (spacings.empty() ? "" : ", ") + format_number(dx.get<double>());
    for (const auto& [name, m] : s.at("metrics").items()) {
      std::string errors;
      for (const json& e : m.at("errors")) errors += (errors.empty() ? "" : ", ") + (e.is_null() ? "n/a" : format_number(e.get<double>()));
      const json& observed = m.at("observed_order");
      o << "| " << s.at("case").get<std::string>() << " | " << s.at("method").get<std::string>() << " | " << name
        << " | " << spacings << " | " << errors << " | "
        << (observed.is_null() ? std::string("n/a") : format_number(observed.get<double>())) << " | "
        << format_number(m.at("expected_order").get<double>()) << " |\n";
    }
    for (const json& r : s.at("runs"))
      if (r.at("status") == "error")
        o << "| " << s.at("case").get<std::string>() << " | " << s.at("method").get<std::string>() << " | error at dx "
          << format_number(r.at("spacing").get<double>()) << " | " << r.at("message").get<std::string>() << " | | | |\n";
  }
  return o.str();
}

}  // namespace sc
