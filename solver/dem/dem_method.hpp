// DEM grains after Rungjiratananon et al. 2008 behind the method seam: DemMethod<D> steps the grains
// of this folder as a Method<D>, a case's sand blocks packed as poured columns, the tank's closed
// sides as contact planes, with DEM's own numbers from the case's "methods": {"dem": {...}}
// object (cases/README.md, docs/equations.md §7). The runs behind the seam are dry: the wetness, bridges and
// SPH-water coupling of this folder are exercised by their unit tests (tests/test_dem.cpp).
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "case/case_file.hpp"
#include "core/stage_timers.hpp"
#include "dem/dem_forces.hpp"
#include "method/adapter.hpp"

namespace sc {

/// DEM's own parameters of a case, "methods"/"dem" (every key optional):
///   friction           grain-grain Coulomb coefficient μ (calibrated per friction angle, docs/references.md §12)
///   rolling_friction   rolling resistance μ_r (torque bound μ_r R_eff |F_n|)
///   wall_friction      Coulomb coefficient of the tank's rough ("no_slip") sides (default: friction);
///                      "slip" sides are frictionless
///   restitution        normal restitution e of a grain pair, in (0, 1]
///   overlap            largest overlap under the weight of the material's full height, as a fraction
///                      of the grain radius (sets the spring stiffness)
///   polydispersity     p: grain radii uniform in [(1 − p), 1] × spacing/2, in [0, 0.5]
///   packed             true: each block starts packed in its mould (make_dem_method); false: its
///                      grains start loose on their lattice sites (a settling scene)
struct DemCaseParams {
  double friction = 0.5;
  double rolling_friction = 0.0;
  double wall_friction = 0.5;
  double restitution = 0.3;
  double overlap = 0.01;
  double polydispersity = 0.15;
  bool packed = true;
};

/// Reads and checks the case's "methods"/"dem" object and that the case is one DEM can run behind
/// the seam (a tank, sand blocks only, gravity). Throws InputError (the case file, the JSON path,
/// the rule). Allocates nothing.
DemCaseParams read_dem_params(const CaseSpec& spec);

namespace dem {
enum class DemStage { Contacts, Integration, Count };
inline constexpr std::array<std::string_view, static_cast<std::size_t>(DemStage::Count)> dem_stage_names = {
    "contacts", "integration"};
}  // namespace dem

template <int D>
class DemMethod final : public ParticleAdapter<D, dem::Grains<D>> {
 public:
  /// Grains, their contact parameters, the tank's planes, gravity and the case's step, split into
  /// `substeps` contact steps.
  DemMethod(dem::Grains<D> grains, const dem::Params& params, std::vector<dem::Plane<D>> walls, const Vec<D>& gravity,
            double dt, int substeps);

  std::string_view name() const override { return "dem"; }
  /// Keeps the grains as the last good state, then advances the case's step in contact substeps.
  double step() override;
  double time() const override { return time_; }
  long steps() const override { return steps_; }
  /// x, v, m (dry mass plus water held), phase (sand); the grain radius as support and the grain's
  /// mass over its volume as density.
  ParticleView<D> particles() const override { return view_of(grains_); }
  /// The contacts' count is their contact steps since the run started.
  std::vector<StageTime> stage_times() const override {
    return stage_times_of(dem::dem_stage_names, timers_, dem::DemStage::Contacts, steps_ * substeps_);
  }
  void reset_stage_times() override { timers_.reset(); }

  const dem::Grains<D>& grains() const { return grains_; }
  const dem::Params& params() const { return params_; }
  int substeps() const { return substeps_; }

 private:
  const dem::Grains<D>& state() const override { return grains_; }
  ParticleView<D> view_of(const dem::Grains<D>& g) const override;

  dem::Grains<D> grains_;
  dem::Params params_;
  std::vector<dem::Plane<D>> walls_;
  Vec<D> gravity_;
  double dt_;
  int substeps_;
  double time_ = 0.0;
  long steps_ = 0;
  dem::NeighbourList<D> cells_;
  StageClock<dem::DemStage> timers_;
  mutable std::vector<double> mass_, density_, support_;  // fields of the last particles() call
  mutable std::vector<std::uint8_t> phase_;
};

/// DEM at t = 0: each of the case's sand blocks packed by settling grains seeded at spacing dx
/// (radii drawn per block from a fixed seed) in a mould of the block, trimmed to its height, the
/// block's mass ρ V shared equally by its grains.
template <int D>
std::unique_ptr<Method<D>> make_dem_method(const CaseSpec& spec, double dx);

}  // namespace sc
