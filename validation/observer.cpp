#include "observer.hpp"

#include <cstdio>

namespace sc {

json MetricLimit::to_json() const {
  if (min && max) return json::array({*min, *max});
  if (max) return *max;
  if (min) return json{{"min", *min}};
  return nullptr;
}

std::map<std::string, MetricLimit> read_metric_limits(JsonObject& validation) {
  std::map<std::string, MetricLimit> out;
  if (!validation.has("metrics")) return out;
  JsonObject metrics = validation.object("metrics");
  for (const auto& [name, value] : validation.raw("metrics").items()) {
    JsonObject m = metrics.object(name);
    MetricLimit limit;
    if (m.has("min")) limit.min = m.number("min");
    if (m.has("max")) limit.max = m.number("max");
    if (limit.min && limit.max && *limit.min > *limit.max) m.fail("min", "must not exceed max");
    m.finish();
    out[name] = limit;
  }
  metrics.finish();
  return out;
}

void add_metric(ObserverResult& r, const std::map<std::string, MetricLimit>& limits, const std::string& name,
                double value) {
  const auto it = limits.find(name);
  r.metrics[name] = Metric{value, it == limits.end() ? MetricLimit{} : it->second};
}

std::string format_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

const Series* find_series(const ObserverResult& r, const std::string& name) {
  for (const Series& s : r.series)
    if (s.name == name) return &s;
  return nullptr;
}

bool is_simulated(const Series& s) { return s.name.find("_sim") != std::string::npos; }

}  // namespace sc
