#include "twin_run.hpp"

namespace sc {

bool run_twin(const CaseSpec& twin, double dx, const RunSettings& settings, const std::string& subdir,
              const std::string& what, RunResult& run, RunResult& twin_result) {
  RunSettings twin_settings;
  twin_settings.out_dir = settings.out_dir + "/" + subdir;
  twin_settings.end_time = settings.end_time;
  twin_settings.label = settings.label + " (" + what + ")";
  twin_settings.decompose = settings.decompose;  // over ranks, one twin on them all, written by rank 0
  twin_result = run_single(twin, dx, twin_settings);
  if (twin_result.status != "error") return true;
  run.status = "error";
  run.exit_code = twin_result.exit_code;
  run.message = what + ": " + twin_result.message;
  return false;
}

void overlay_twin(const Series& twin, const std::string& name, const std::string& prefix, const std::string& label,
                  ObserverResult& r) {
  Series renamed = twin;
  renamed.name = prefix + "_" + name;
  r.series.push_back(renamed);
  for (Plot& p : r.plots)
    for (std::size_t c = 0, n = p.curves.size(); c < n; ++c)
      if (p.curves[c].series == name) p.curves.push_back({renamed.name, label, "line"});
}

std::vector<std::string> twin_names(JsonObject& twin, const std::string& key) {
  std::vector<std::string> names;
  if (!twin.has(key)) return names;
  for (const json& name : twin.raw(key)) {
    if (!name.is_string()) twin.fail(key, "must be an array of names (strings)");
    names.push_back(name.get<std::string>());
  }
  return names;
}

}  // namespace sc
