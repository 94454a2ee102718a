// Measurements shared by the porous-flow observers: the water balance (docs/references.md §8), the
// saturation bounds, and horizontal-row averages over the central band of a porous column.
#pragma once
#include <algorithm>
#include <cmath>
#include <vector>

#include "method/method.hpp"
#include "observers/line_fit.hpp"
#include "porous/porous_flow.hpp"
#include "simulator/sph_probe.hpp"

namespace sc {

/// Free water plus absorbed water, against its value at the first sample; and the saturation
/// m_p/(ρ^f φ V) of every porous particle *before* eq 21's clamp, so that a limiter failure shows.
/// Needs the view's porosity and pore volume φ V, and its held water; a method whose pore water is
/// free water (MPM: no held water) is bounded by the saturation its view reports.
template <int D>
class WaterBalanceProbe {
 public:
  WaterBalanceProbe() = default;
  /// ρ^f of the absorbed water (the case's porous section).
  explicit WaterBalanceProbe(double fluid_density) : fluid_density_(fluid_density) {}

  void sample(const Method<D>& run) {
    const ParticleView<D> ps = run.particles();
    const double total = total_water(ps);
    if (first_) { initial_ = total; first_ = false; }
    error_ = std::max(error_, std::abs(total - initial_) / initial_);
    for (std::size_t i = 0; i < ps.size(); ++i) {
      if (!is_porous_phase(ps.phase_of(i), ps.porosity[i])) continue;
      const double S = ps.held_water.empty() ? ps.saturation[i] : ps.held_water[i] / (fluid_density_ * ps.pore_volume[i]);
      s_min_ = std::min(s_min_, S);
      s_max_ = std::max(s_max_, S);
    }
  }
  double relative_error() const { return error_; }
  /// How far any raw saturation left [0, 1] (0 if never), with a round-off allowance of 1e-12.
  double saturation_violation() const { return std::max({0.0, -s_min_ - 1e-12, s_max_ - 1.0 - 1e-12}); }

 private:
  double fluid_density_ = 0.0;
  bool first_ = true;
  double initial_ = 0.0, error_ = 0.0, s_min_ = 0.0, s_max_ = 1.0;
};

/// Volume of a water mass as the lattice holds it [m^D]: a full water particle of the scene's
/// sampling (mass `full_water_mass`) fills one site, dx^D, and the pores of a site hold water by the
/// same measure (solver/porous/porous_volume.hpp). Pond depths, infiltrated and drained water.
template <int D>
double lattice_water_volume(double mass, double full_water_mass, double dx) {
  return mass / full_water_mass * std::pow(dx, D);
}

/// The mass of a full water particle of `run` at spacing dx: SPH's (SphProbe::full_water_mass), or
/// ρ dx^D for a method that seeds every lattice site of water with that mass (MPM).
template <int D>
double full_water_mass(const Method<D>& run, double rho, double dx) {
  return run.name() == "sph" ? require_sph(run, "full_water_mass").full_water_mass() : rho * std::pow(dx, D);
}

/// Porous (fixed-skeleton) particles whose x lies in [lo, hi]: the central band of a column.
template <int D>
bool in_porous_band(const ParticleView<D>& ps, std::size_t i, double lo, double hi) {
  return ps.phase_of(i) == Phase::Boundary && ps.porosity[i] > 0.0 && ps.x[i][0] >= lo && ps.x[i][0] <= hi;
}

/// Mean of `field` over the porous particles of the band, in rows one spacing high from `z0`.
template <int D>
std::vector<double> row_means(const ParticleView<D>& ps, std::span<const double> field, double lo, double hi,
                              double z0, double dx, std::size_t rows) {
  std::vector<double> sum(rows, 0.0), count(rows, 0.0);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (!in_porous_band(ps, i, lo, hi)) continue;
    const double k = std::floor((ps.x[i][D - 1] - z0) / dx);
    if (k < 0.0 || k >= static_cast<double>(rows)) continue;
    sum[static_cast<std::size_t>(k)] += field[i];
    count[static_cast<std::size_t>(k)] += 1.0;
  }
  for (std::size_t k = 0; k < rows; ++k) sum[k] = count[k] > 0.0 ? sum[k] / count[k] : NAN;
  return sum;
}

}  // namespace sc
