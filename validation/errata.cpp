#include "errata.hpp"

#include <filesystem>
#include <iostream>
#include <sstream>

#include "case/case_file.hpp"
#include "observer.hpp"
#include "run_record.hpp"

namespace sc {

namespace {

/// Metrics of a run as report.json writes them: value (null when not finite) and pass.
json run_metrics(const RunResult& r) {
  json out = json::object();
  for (const auto& [name, m] : r.observed.metrics)
    out[name] = {{"value", std::isfinite(m.value) ? json(m.value) : json(nullptr)}, {"pass", m.pass()}};
  return out;
}

/// The corrected form's run: the finest resolution of the normal run's case entry.
json corrected_run(const json& entry) {
  json out = {{"status", entry.at("status")}, {"metrics", json::object()}};
  if (!entry.contains("resolutions") || entry.at("resolutions").empty()) return out;
  const json& fine = entry.at("resolutions").back();
  out["steps"] = fine.at("steps");
  for (const auto& [name, m] : fine.at("metrics").items())
    out["metrics"][name] = {{"value", m.at("value")}, {"pass", m.at("pass")}};
  return out;
}

/// The printed form's run of one case: status, steps, metrics, or the step at which it blew up.
json printed_run(const std::string& file, const Erratum& e, const ValidateOptions& opt, const std::string& case_name) {
  const CaseSpec spec = load_case(patched_case_document(file, e.patch), file);
  const TierSpec& tier = spec.tiers.at(opt.tier);
  RunSettings settings;
  settings.out_dir = opt.out_dir + "/errata/eq" + e.equation + "/" + case_name;
  settings.end_time = tier.end_time;
  settings.label = case_name + " (eq " + e.equation + " printed)";
  const RunResult r = run_simulation(spec, tier.spacings.back(), settings);
  json out = {{"status", r.status}, {"steps", r.steps}, {"spacing", r.spacing}, {"metrics", run_metrics(r)}};
  out["blew_up_at_step"] = r.exit_code == kBlowUp ? json(r.steps) : json(nullptr);
  if (!r.message.empty()) out["message"] = r.message;
  return out;
}

const json* find_entry(const std::vector<json>& entries, const std::string& name) {
  for (const json& e : entries)
    if (run_key(e) == name) return &e;  // the run by the case's own method
  return nullptr;
}

std::string metric_cell(const json& run, const std::string& name) {
  if (!run.at("metrics").contains(name)) return "n/a";
  const json& m = run.at("metrics").at(name);
  const std::string value = m.at("value").is_null() ? "n/a" : format_number(m.at("value").get<double>());
  return value + (m.at("pass").get<bool>() ? "" : " **FAIL**");
}

}  // namespace

const std::vector<Erratum>& errata_table() {
  static const std::vector<Erratum> table = {
      {"4", "Müller's halved (P_i + P_j)/2: half the pressure gradient", {{"water", {{"mueller_half_pressure", true}}}},
       {"hydrostatic", "dam_break_square"}},
      {"10", "yield surface with k = 1: flowing sand lies outside it", {{"sand", {{"yield_surface", "zhu_bridson"}}}},
       {"column_collapse", "angle_of_repose"}},
      {"12a", "rigid stress with the support h for the spacing", {{"sand", {{"rigid_stress_length", "support"}}}},
       {"column_collapse", "angle_of_repose"}},
      {"17", "inertia with I_yy = Σ m (y² + z²): wrong moment about y", {{"sand", {{"inertia_tensor", "printed"}}}},
       {"sand_water_adaptive_3d", "column_collapse_3d", "rigid_spin_3d"}},
      {"22", "plain gradient Σ V_j A_j ∇W: spurious edge gradient", {{"porous", {{"gradient", "lenaerts"}}}},
       {"green_ampt", "darcy_column", "capillary_rise"}},
      {"25", "inverted density ratio: squeezed sand sucks water in", {{"porous", {{"thesis_pore_pressure_ratio", true}}}},
       {"wet_sand_collapse"}},
      {"28", "literal diffusion (Lenaerts' case B): not conservative", {{"porous", {{"diffusion", "lenaerts_literal"}}}},
       {"green_ampt", "darcy_column", "capillary_rise"}},
  };
  return table;
}

json patched_case_document(const std::string& file, const json& patch) {
  json doc = read_json_file(file);
  doc.merge_patch(patch);
  return doc;
}

json run_errata(const ValidateOptions& opt, const std::string& cases_dir, const std::vector<json>& entries) {
  json section = json::array();
  for (const Erratum& e : errata_table()) {
    json runs = json::array();
    for (const std::string& name : e.cases) {
      const json* entry = find_entry(entries, name);
      if (!entry || !entry->contains("resolutions")) continue;  // not run in this validation
      const std::string file = cases_dir + "/" + name + "/case.json";
      json printed;
      try {
        printed = printed_run(file, e, opt, name);
      } catch (const InputError& err) {  // the printed form refused by the case's readers
        printed = {{"status", "error"}, {"message", err.what()}, {"blew_up_at_step", nullptr}, {"metrics", json::object()}};
      }
      runs.push_back({{"case", name}, {"corrected", corrected_run(*entry)}, {"printed", printed}});
    }
    section.push_back({{"equation", e.equation}, {"printed_form", e.printed}, {"switch", e.patch}, {"cases", runs}});
  }
  return section;
}

std::string errata_markdown(const json& report) {
  if (!report.contains("errata")) return "";
  std::ostringstream o;
  o << "\n## Errata impact (printed form against the corrected one)\n\n"
    << "| eq | switch | case | metric | corrected | printed |\n|---|---|---|---|---|---|\n";
  for (const json& e : report.at("errata")) {
    const std::string head = "| " + e.at("equation").get<std::string>() + " | `" + e.at("switch").dump() + "` | ";
    if (e.at("cases").empty()) o << head << "(no affected case in this run) | | | |\n";
    for (const json& c : e.at("cases")) {
      const json& printed = c.at("printed");
      const std::string row = head + c.at("case").get<std::string>() + " | ";
      if (!printed.at("blew_up_at_step").is_null()) {
        o << row << "all | " << c.at("corrected").at("status").get<std::string>() << " | blew up at step "
          << printed.at("blew_up_at_step") << " |\n";
        continue;
      }
      for (const auto& [name, m] : c.at("corrected").at("metrics").items())
        o << row << name << " | " << metric_cell(c.at("corrected"), name) << " | " << metric_cell(printed, name) << " |\n";
    }
  }
  return o.str();
}

}  // namespace sc
