#include "run_record.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "reference_data.hpp"

namespace sc {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

bool strictly_increasing(const std::vector<double>& v) {
  for (std::size_t k = 1; k < v.size(); ++k)
    if (!(v[k] > v[k - 1])) return false;
  return !v.empty();
}

/// A series as (abscissa, value) with the kind of abscissa: "x", "y" or "index".
struct Oriented {
  std::string kind;
  std::vector<double> t, v;
};

Oriented orient(const Series& s) {
  if (strictly_increasing(s.x)) return {"x", s.x, s.y};
  if (strictly_increasing(s.y)) return {"y", s.y, s.x};
  std::vector<double> index(s.y.size());
  for (std::size_t k = 0; k < index.size(); ++k) index[k] = static_cast<double>(k);
  return {"index", index, s.y};
}

double json_number(const json& j) { return j.is_number() ? j.get<double>() : NAN; }

/// The numbers of a series array; null (how finite_or_null writes a NaN) reads back as NaN.
std::vector<double> series_values(const json& array) {
  if (!array.is_array()) throw json::type_error::create(302, "series values must be an array", &array);
  std::vector<double> out;
  out.reserve(array.size());
  for (const json& v : array) {
    if (!v.is_number() && !v.is_null()) throw json::type_error::create(302, "series values must be numbers or null", &v);
    out.push_back(json_number(v));
  }
  return out;
}

}  // namespace

json finite_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

std::vector<Series> series_from_json(const json& series_array, const std::string& file) {
  std::vector<Series> out;
  try {
    for (const json& s : series_array)
      out.push_back({s.at("name"), s.value("x_label", ""), s.value("y_label", ""),
                     series_values(s.at("x")), series_values(s.at("y"))});
  } catch (const json::exception& e) {
    throw InputError(file, "/series", std::string("malformed series: ") + e.what());
  }
  return out;
}

std::string run_key(const json& entry) { return entry.value("run_id", entry.at("name").get<std::string>()); }

RunRecord record_from_entry(const json& entry, const std::string& run_dir) {
  RunRecord r;
  r.name = entry.at("name");
  r.tier = entry.at("tier");
  r.status = entry.at("status");
  r.checksum = entry.at("state_checksum").is_string() ? entry.at("state_checksum").get<std::string>() : "";
  r.parameters_hash = entry.value("parameters_hash", "");
  r.spacing = entry.value("spacing", 0.0);
  for (const auto& [name, m] : entry.at("metrics").items()) r.metrics[name] = json_number(m.at("value"));
  if (entry.at("series").is_string()) {
    const std::string file = (std::filesystem::path(run_dir) / entry.at("series").get<std::string>()).string();
    r.series = series_from_json(read_json_file(file).at("series"), file);
  }
  return r;
}

SeriesDelta series_difference(const Series& base, const Series& other) {
  const Oriented b = orient(base), o = orient(other);
  if (b.kind != o.kind) return {kInf, kInf, "abscissa changed from " + b.kind + " to " + o.kind};
  if (b.t.empty() || o.t.empty()) return {kInf, kInf, "empty series"};
  double diff2 = 0.0, base2 = 0.0, worst = 0.0;
  for (std::size_t k = 0; k < b.t.size(); ++k) {
    const double d = interpolate_linear(o.t, o.v, b.t[k]) - b.v[k];
    diff2 += d * d;
    base2 += b.v[k] * b.v[k];
    worst = std::max(worst, std::abs(d));
  }
  const double relative = base2 > 0.0 ? std::sqrt(diff2 / base2) : (diff2 > 0.0 ? kInf : 0.0);
  return {relative, worst, ""};
}

Series thinned(const Series& s, std::size_t max_points) {
  if (s.x.size() <= max_points || orient(s).kind == "index") return s;
  const std::size_t stride = (s.x.size() + max_points - 2) / (max_points - 1);
  Series out{s.name, s.x_label, s.y_label, {}, {}};
  for (std::size_t k = 0; k < s.x.size(); k += stride) {
    out.x.push_back(s.x[k]);
    out.y.push_back(s.y[k]);
  }
  if (out.x.back() != s.x.back()) {
    out.x.push_back(s.x.back());
    out.y.push_back(s.y.back());
  }
  return out;
}

MetricDelta metric_difference(double base, double other) {
  if (std::isnan(base) && std::isnan(other)) return {0.0, 0.0};
  if (std::isnan(base) || std::isnan(other)) return {kInf, kInf};
  const double delta = other - base;
  return {delta, base != 0.0 ? std::abs(delta / base) : (delta != 0.0 ? kInf : 0.0)};
}

}  // namespace sc
