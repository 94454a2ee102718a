// What a run with adaptivity (case section "adaptive") reports beyond its observer's metrics:
// the conservation account of its split/merge passes and, when the validation block asks for a
// "uniform_twin", the comparison with the same case run at the finest level without adaptivity.
#pragma once
#include "case/case_file.hpp"
#include "runner.hpp"

namespace sc {

/// Adds to run.observed (limits from the case's validation.metrics; none = informational):
///   adaptive_mass_rel_error, adaptive_momentum_error, adaptive_moment_error (Σ m x: the centre of mass),
///   adaptive_water_rel_error: the largest error of one pass (docs/references.md §7: exact);
///   merge_energy_removed [J], splits, merges;
/// and, with "uniform_twin": {"series": [NAME, ...], "metrics": [METRIC, ...]} (both optional) in
/// the validation block, runs the case without its "adaptive" section into <out>/uniform and adds
///   <NAME without "_sim">_vs_uniform_rms: series_difference (relative RMS) of each named series,
///   <METRIC>_vs_uniform_ratio: the adaptive run's metric / the uniform run's,
///   particle_ratio: mean moving particles, uniform / adaptive,
///   (no wall-time metric: timings vary run to run and would make baselines flaky; `sandcastle
///   bench` compares the speed of an adaptive scene with its uniform twin),
/// with the twin's series (prefixed "uniform_") overlaid on the plots, and a plot of the
/// moving particles against time for both runs.
void add_adaptive_results(const CaseSpec& spec, double dx, const RunSettings& settings, RunResult& run);

}  // namespace sc
