// The roofline of `sandcastle bench` (docs/performance.md, "The model of an SPH step"): for each
// pair stage of an SPH step (neighbour search, density, forces), the pair evaluations it does per
// step, the flops and bytes those take by the model's cost per evaluation, the floor time the
// machine's limits (the probe, validation/probe.hpp) allow for them, and the share of that floor
// the measured stage time reaches.
#pragma once
#include <string>

#include "io/json_reader.hpp"
#include "probe.hpp"

namespace sc {

/// The neighbour-list entries of one step, by the phase of the particle whose list it is.
struct ListEntries {
  double water = 0.0, sand = 0.0, boundary = 0.0;
  double moving() const { return water + sand; }
  double total() const { return water + sand + boundary; }
};

/// The limits a bench run is read against: the probe's row at the run's thread count, from
/// probe.json (`file`) or measured now at that thread count only (file empty). A probe.json without that row, or not a probe
/// document, is bad input (InputError naming the file and the JSON path).
ProbeRow bench_limits(const std::string& file, int threads);

/// bench.json's "roofline" of one SPH scene: the limits, the list entries, and per stage
/// ("neighbours", "density", "forces") its pair evaluations per step and per second, flops and
/// bytes per step, bytes per particle, floor time, what bounds it and the fraction of the limit it
/// reaches. `stage_ms`: bench.json's stage_ms_per_step; `corrected`: the scene uses the gradient
/// correction (one more pass over the moving particles' lists in "forces").
json roofline(int dimension, const ListEntries& entries, double particles, const json& stage_ms, bool corrected,
              const ProbeRow& limits, const std::string& limits_source);

}  // namespace sc
