// Loss of cohesion of wetted sand (our decision; the thesis gives no law, see below).
#pragma once
#include <algorithm>

namespace sc {

/// Cohesion c [Pa] of the yield test (eq 10) of sand at saturation S:
///   c(S) = c0 (1 − S),
/// the law of Tampubolon et al. 2017 (multi-species MPM for sand and water, c_C = c_C^0 (1 − φ_w);
/// seeds/004) for a sculpture whose strength comes from its packing and pore suction: full at
/// S = 0, gone when saturated. The thesis (§3.3) only writes c in eq 10 and Lenaerts et al. 2008
/// weaken wet material by eq 32 alone, so the form is a choice of ours (docs/equations.md, "Wet cohesion");
/// eq 32 then removes friction on top of it. S is clamped to [0, 1].
inline double wet_cohesion(double dry_cohesion, double saturation) {
  return dry_cohesion * (1.0 - std::clamp(saturation, 0.0, 1.0));
}

}  // namespace sc
