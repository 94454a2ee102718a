// Effective stress of wet sand (Terzaghi; Lenaerts et al. 2008 eq 12).
#pragma once
#include <algorithm>

namespace sc {

/// Effective stress [thesis eq. 32] (Lenaerts eq 12): σ^eff = σ − η P^{p*} I with P^{p*} = k^p S,
/// for Lenaerts' tension-positive elastic stress: the pore water pushes the skeleton apart.
/// The thesis' sand has no elastic stress; its analogue for the compression-positive Zhu-Bridson
/// friction and yield (eqs 8, 10) is Terzaghi's effective pressure (docs/equations.md, eq 32):
///   p' = max(0, p − η k^p S),
/// which the sand model uses in place of p, so wetter sand has less friction and yields earlier.
/// Do not subtract η k^p S from the compression-positive σ_f directly (that would add pressure).
inline double effective_pressure(double pressure, double eta, double kp, double saturation) {
  return std::max(0.0, pressure - eta * kp * saturation);
}

}  // namespace sc
