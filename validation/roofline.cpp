#include "roofline.hpp"

#include <cmath>
#include <numbers>
#include <vector>

#include "core/errors.hpp"

namespace sc {

namespace {

/// One kind of pass over neighbour lists: what one pair evaluation costs by the model
/// (docs/performance.md, table "Cost of a pair evaluation"). Counted as written in the solver's
/// loops: a subtraction per coordinate for x_i − x_j, D products and D − 1 sums for r², the
/// square root as one flop, each kernel's arithmetic; bytes are what a neighbour's entry reads (its
/// fields, 8 bytes each, and the 4-byte list entry), as if from memory (no reuse in cache).
struct PassCost {
  double flops, bytes;
};

/// Candidates tested per list entry by the cell search (cells of the support's size): the 3^D
/// cells around a particle against the ball of the support.
double candidates_per_entry(int D) { return D == 3 ? 27.0 / (4.0 / 3.0 * std::numbers::pi) : 9.0 / std::numbers::pi; }

struct Pass {
  std::string stage;
  double evaluations;
  PassCost cost;
};

/// The passes of a step: `d` dimensions, list entries `e`.
std::vector<Pass> passes(int d, const ListEntries& e, bool corrected) {
  const double D = d, r = 3.0 * D;  // r: x_i − x_j, |x_i − x_j|² and the square root
  std::vector<Pass> p = {
      // Cell search: r² of each candidate and the two support tests; reads x and h² of the candidate;
      // every entry found is written once (4 bytes, spread over its candidates).
      {"neighbours", candidates_per_entry(d) * e.total(), {r + 1.0, 8.0 * (D + 1.0) + 4.0 / candidates_per_entry(d)}},
      // Density sum of the moving particles: spiky kernel and m_j W; reads x, m, h.
      {"density", e.moving(), {r + 6.0, 8.0 * (D + 2.0) + 4.0}},
      // Wall pressure from the moving neighbours: kernel, weighted pressure, hydrostatic term; reads x, h, m, ρ, p.
      {"density", e.boundary, {r + 8.0 + 2.0 * D, 8.0 * (D + 4.0) + 4.0}},
      // Water forces: pressure, viscosity and surface-tension pair terms, the corrected pressure term
      // ½(L_i + L_j) f (D² sums, D² products, D(D − 1) sums, D products); reads x, v, h, m, ρ, p, L.
      {"forces", e.water, {r + 20.0 + 6.0 * D + 3.0 * D * D, 8.0 * (2.0 * D + 4.0 + D * D) + 6.0}},
      // Sand: velocity gradient, pressure/contact/viscosity forces, frictional forces, each as a water force pass.
      {"forces", 3.0 * e.sand, {r + 20.0 + 6.0 * D + 3.0 * D * D, 8.0 * (2.0 * D + 4.0 + D * D) + 6.0}},
  };
  // Moment matrix of the gradient correction: spiky derivative, one division, D(D + 1)/2 sums of products; reads x, h, m, ρ.
  if (corrected) p.push_back({"forces", e.moving(), {r + 6.0 + D * (D + 1.0), 8.0 * (D + 3.0) + 4.0}});
  return p;
}

}  // namespace

ProbeRow bench_limits(const std::string& file, int threads) {
  if (file.empty()) return probe_row(threads);
  const json doc = read_json_file(file);
  if (!doc.is_object() || !doc.contains("rows") || !doc["rows"].is_array())
    throw InputError(file, "/rows", "must be an array of the probe's rows (sandcastle bench --probe)");
  for (std::size_t k = 0; k < doc["rows"].size(); ++k) {
    const json& row = doc["rows"][k];
    const std::string at = "/rows/" + std::to_string(k);
    if (!row.is_object() || !row.contains("threads") || !row["threads"].is_number_integer())
      throw InputError(file, at + "/threads", "must be an integer");
    if (row["threads"].get<int>() != threads) continue;
    for (const char* key : {"bandwidth_bytes_per_s", "flops_per_s"})
      if (!row.contains(key) || !row[key].is_number() || !(row[key].get<double>() > 0.0))
        throw InputError(file, at + "/" + key, "must be a positive number");
    return {threads, row["bandwidth_bytes_per_s"].get<double>(), row["flops_per_s"].get<double>()};
  }
  throw InputError(file, "/rows", "has no row for " + std::to_string(threads) + " threads (the bench's thread count)");
}

json roofline(int dimension, const ListEntries& entries, double particles, const json& stage_ms, bool corrected,
              const ProbeRow& limits, const std::string& limits_source) {
  json stages = json::object();
  for (const Pass& p : passes(dimension, entries, corrected)) {
    json& s = stages[p.stage];
    if (s.is_null()) s = {{"pair_evaluations_per_step", 0.0}, {"flops_per_step", 0.0}, {"bytes_per_step", 0.0}};
    s["pair_evaluations_per_step"] = s["pair_evaluations_per_step"].get<double>() + p.evaluations;
    s["flops_per_step"] = s["flops_per_step"].get<double>() + p.evaluations * p.cost.flops;
    s["bytes_per_step"] = s["bytes_per_step"].get<double>() + p.evaluations * p.cost.bytes;
  }
  for (auto& [name, s] : stages.items()) {
    const double seconds = stage_ms.value(name, 0.0) / 1e3;
    const double memory = s["bytes_per_step"].get<double>() / limits.bandwidth;
    const double compute = s["flops_per_step"].get<double>() / limits.flops;
    s["bytes_per_particle"] = s["bytes_per_step"].get<double>() / particles;
    s["floor_ms"] = 1e3 * std::max(memory, compute);
    s["bound"] = memory >= compute ? "memory" : "compute";
    if (seconds > 0.0) {
      s["pair_evaluations_per_s"] = s["pair_evaluations_per_step"].get<double>() / seconds;
      s["fraction_of_limit"] = std::max(memory, compute) / seconds;
    }
  }
  return {{"limits",
           {{"threads", limits.threads},
            {"bandwidth_bytes_per_s", limits.bandwidth},
            {"flops_per_s", limits.flops},
            {"source", limits_source}}},
          {"list_entries",
           {{"water", entries.water}, {"sand", entries.sand}, {"boundary", entries.boundary}, {"total", entries.total()}}},
          {"stages", stages}};
}

}  // namespace sc
