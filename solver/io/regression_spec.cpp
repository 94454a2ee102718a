#include "io/regression_spec.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>

namespace sc {

namespace {

/// Keys the case format ignores (JsonObject::finish): "comment" and names starting with '_'.
bool is_note(const std::string& key) { return key == "comment" || key.rfind("_", 0) == 0; }

DifferenceLimit read_limit(JsonObject o) {
  DifferenceLimit limit;
  if (o.has("relative")) limit.relative = o.non_negative("relative", 0.0);
  if (o.has("absolute")) limit.absolute = o.non_negative("absolute", 0.0);
  if (!limit.relative && !limit.absolute) o.fail("relative", "set \"relative\", \"absolute\" or both");
  o.finish();
  return limit;
}

/// Reads {"*": limit, NAME: limit, ...}: the default into `fallback`, the rest by name.
void read_limits(JsonObject o, DifferenceLimit& fallback, std::map<std::string, DifferenceLimit>& by_name,
                 const json& raw) {
  for (const auto& [name, value] : raw.items()) {
    if (is_note(name)) continue;
    const DifferenceLimit limit = read_limit(o.object(name));
    if (name == "*") fallback = limit;
    else by_name[name] = limit;
  }
  o.finish();
}

json without_notes(const json& j) {
  if (j.is_array()) {
    json out = json::array();
    for (const json& v : j) out.push_back(without_notes(v));
    return out;
  }
  if (!j.is_object()) return j;
  json out = json::object();
  for (const auto& [key, value] : j.items())
    if (!is_note(key)) out[key] = without_notes(value);
  return out;
}

}  // namespace

bool DifferenceLimit::accepts(double relative_value, double absolute_value) const {
  const bool rel_ok = !relative || (std::isfinite(relative_value) && relative_value <= *relative);
  const bool abs_ok = !absolute || (std::isfinite(absolute_value) && absolute_value <= *absolute);
  return rel_ok && abs_ok;
}

json DifferenceLimit::to_json() const {
  json out = json::object();
  if (relative) out["relative"] = *relative;
  if (absolute) out["absolute"] = *absolute;
  return out;
}

const DifferenceLimit& RegressionSpec::for_series(const std::string& name) const {
  const auto it = series.find(name);
  return it == series.end() ? series_default : it->second;
}

const DifferenceLimit& RegressionSpec::for_metric(const std::string& name) const {
  const auto it = metrics.find(name);
  return it == metrics.end() ? metric_default : it->second;
}

RegressionSpec read_regression(JsonObject o) {
  RegressionSpec spec;
  if (o.has("series")) read_limits(o.object("series"), spec.series_default, spec.series, o.raw("series"));
  if (o.has("metrics")) read_limits(o.object("metrics"), spec.metric_default, spec.metrics, o.raw("metrics"));
  o.finish();
  return spec;
}

std::string parameters_hash(const json& case_document) {
  json j = without_notes(case_document);
  j.erase("description");
  j.erase("regression");
  j.erase("convergence");  // the spacings of a study: each run records its own spacing
  j.erase("render");  // how a run is drawn (validation/render) is no parameter of it
  j.erase("methods");  // other methods' parameters; a run by one of them adds its own (method/registry.cpp)
  if (j.contains("tiers"))  // which methods a tier runs is no parameter of any run
    for (auto& [name, tier] : j["tiers"].items())
      if (tier.is_object()) tier.erase("methods");
  std::uint64_t hash = 1469598103934665603ull;
  for (const unsigned char c : j.dump()) {
    hash ^= c;
    hash *= 1099511628211ull;
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(hash));
  return buf;
}

}  // namespace sc
