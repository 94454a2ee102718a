// The "dry twin" of a wet-sand case: the same case run without its water, so that what the water
// did (weakening the sand, eqs 32 and the wet cohesion) is measured against the dry run.
#pragma once
#include "case/case_file.hpp"
#include "runner.hpp"

namespace sc {

/// With "dry_twin": {"metrics": [METRIC, ...], "series": [NAME, ...]} in the validation block,
/// runs the case without its water blocks into <out>/dry and adds to run.observed (limits from
/// the case's validation.metrics; none = informational):
///   <METRIC>_dry:  the dry run's metric,
///   <METRIC>_gain: the wet run's metric minus the dry run's,
/// and overlays the dry run's series (prefixed "dry_") on the plots. A metric out of its limits
/// fails the run. No "dry_twin" block: nothing happens.
void add_dry_twin_results(const CaseSpec& spec, double dx, const RunSettings& settings, RunResult& run);

}  // namespace sc
