#include "methods_report.hpp"

#include <algorithm>
#include <sstream>

#include "runner.hpp"

namespace sc {

namespace {

/// Metric names of every run, in the order the first run lists them, then any others.
std::vector<std::string> metric_names(const std::vector<MethodRun>& runs) {
  std::vector<std::string> names;
  for (const MethodRun& r : runs)
    for (const auto& [name, m] : r.entry.at("metrics").items())
      if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  return names;
}

json metrics_side_by_side(const std::vector<MethodRun>& runs) {
  json out = json::object();
  for (const std::string& name : metric_names(runs)) {
    json values = json::object(), pass = json::object(), limit = nullptr;
    for (const MethodRun& r : runs) {
      const json& metrics = r.entry.at("metrics");
      if (!metrics.contains(name)) {
        values[r.method] = nullptr;
        pass[r.method] = nullptr;
        continue;
      }
      values[r.method] = metrics.at(name).at("value");
      pass[r.method] = metrics.at(name).at("pass");
      if (limit.is_null()) limit = metrics.at(name).at("limit");
    }
    out[name] = {{"limit", limit}, {"values", values}, {"pass", pass}};
  }
  return out;
}

}  // namespace

ObserverResult methods_overlay(const std::vector<MethodRun>& runs) {
  ObserverResult out;
  const ObserverResult& first = runs.front().observed;
  for (const Plot& plot : first.plots) {
    Plot overlay{"methods_" + plot.file, plot.title + ", by method", plot.x_label, plot.y_label, {}};
    for (const Curve& c : plot.curves) {
      const Series* own = find_series(first, c.series);
      if (own && !is_simulated(*own)) {  // a reference: once
        if (!find_series(out, own->name)) out.series.push_back(*own);
        overlay.curves.push_back(c);
        continue;
      }
      for (const MethodRun& r : runs) {
        const Series* s = find_series(r.observed, c.series);
        if (!s) continue;
        Series renamed = *s;
        renamed.name = s->name + "@" + r.method;
        if (!find_series(out, renamed.name)) out.series.push_back(renamed);
        overlay.curves.push_back({renamed.name, c.label + " (" + r.method + ")", c.style});
      }
    }
    out.plots.push_back(overlay);
  }
  return out;
}

json methods_comparison(const CaseSpec& spec, const std::vector<MethodRun>& runs, const std::string& out_dir) {
  json methods = json::array(), status = json::object(), ids = json::object();
  for (const MethodRun& r : runs) {
    methods.push_back(r.method);
    status[r.method] = r.entry.at("status");
    ids[r.method] = r.entry.at("run_id");
  }
  const std::string folder = runs.front().entry.at("run_id");
  const ObserverResult overlay = methods_overlay(runs);
  write_series_file(out_dir + "/" + folder + "/methods.json", spec.name, overlay);
  json plots = json::array();
  for (const Plot& p : overlay.plots) plots.push_back(folder + "/" + p.file);
  return {{"name", spec.name}, {"methods", methods}, {"run_ids", ids}, {"status", status},
          {"metrics", metrics_side_by_side(runs)}, {"series", folder + "/methods.json"}, {"plots", plots}};
}

std::string methods_markdown(const json& report) {
  if (!report.contains("methods") || report.at("methods").empty()) return "";
  std::ostringstream o;
  o << "\n## Methods side by side\n";
  for (const json& c : report.at("methods")) {
    const std::vector<std::string> methods = c.at("methods");
    o << "\n### " << c.at("name").get<std::string>() << "\n\n| metric | gate |";
    for (const std::string& m : methods) o << " " << m << " (" << c.at("status").at(m).get<std::string>() << ") |";
    o << "\n|---|---|";
    for (std::size_t k = 0; k < methods.size(); ++k) o << "---|";
    o << "\n";
    for (const auto& [name, item] : c.at("metrics").items()) {
      o << "| " << name << " | " << item.at("limit").dump() << " |";
      for (const std::string& m : methods) {
        const json& v = item.at("values").at(m);
        const json& pass = item.at("pass").at(m);
        o << " " << (v.is_number() ? format_number(v.get<double>()) : std::string("n/a"))
          << (pass.is_boolean() && !pass.get<bool>() ? " **FAIL**" : "") << " |";
      }
      o << "\n";
    }
  }
  return o.str();
}

}  // namespace sc
