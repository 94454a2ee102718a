// DEM grains after Rungjiratananon et al. 2008 behind the method seam: DemMethod<D> steps the grains
// of this folder as a Method<D>, a case's sand blocks packed as poured columns, the tank's closed
// sides as contact planes, with DEM's own numbers from the case's "methods": {"dem": {...}}
// object (cases/README.md, docs/equations.md §7). A case's water blocks become the project's SPH
// water (solver/simulator/), stepped by the adapter beside the grains and coupled to them by
// solver/dem/water_coupling.hpp (docs/equations.md §7.9).
#pragma once
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "case/case_file.hpp"
#include "core/stage_timers.hpp"
#include "dem/dem_forces.hpp"
#include "dem/water_coupling.hpp"
#include "method/adapter.hpp"
#include "simulator/simulator.hpp"

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
///   moisture           saturation every grain holds at the start, in [0, wet_threshold]
///   wet_threshold      w_f, the saturation above which a grain is over-wet, in (0, 1]
///   propagation_rate   k_p [1/s] of wetness propagation; k_p times the case's step at most 1
///   bridges            true: Willett bridges between moist grains, their pull-off force from the
///                      case's sand cohesion (needs one > 0; docs/equations.md §7.8)
struct DemCaseParams {
  double friction = 0.5;
  double rolling_friction = 0.0;
  double wall_friction = 0.5;
  double restitution = 0.3;
  double overlap = 0.01;
  double polydispersity = 0.15;
  bool packed = true;
  double moisture = 0.0;
  double wet_threshold = 0.5;
  double propagation_rate = 0.0;
  bool bridges = false;
};

/// Reads and checks the case's "methods"/"dem" object and that the case is one DEM can run behind
/// the seam (a tank, sand and water blocks only, gravity). Throws InputError (the case file, the JSON
/// path, the rule). Allocates nothing.
DemCaseParams read_dem_params(const CaseSpec& spec);

namespace dem {
enum class DemStage { Contacts, Integration, Water, Count };
inline constexpr std::array<std::string_view, static_cast<std::size_t>(DemStage::Count)> dem_stage_names = {
    "contacts", "integration", "water"};
}  // namespace dem

/// What the view of a DEM run shows at one moment: the grains, then the SPH water's particles
/// (water and its tank's wall particles), field by field (the adapter's state: its checksum hashes
/// x and v in this order, and the last good one is a copy).
template <int D>
struct DemFrame {
  typename dem::Grains<D>::VecArray x, v;
  std::vector<double> m, density, support;
  std::vector<std::uint8_t> phase;
  bool wet = false;  ///< the run holds water: the fields below are filled
  /// Per grain: its capacity fraction c_f as porosity, c_f V as pore volume, the water it holds and
  /// its saturation; zero on the SPH particles.
  std::vector<double> porosity, pore_volume, held, saturation;
  std::size_t size() const { return x.size(); }
};

template <int D>
class DemMethod final : public ParticleAdapter<D, DemFrame<D>> {
 public:
  /// Grains, their contact parameters, the tank's planes, gravity, the case's step and the longest
  /// contact step; `water`: the SPH water the grains exchange with (none in a run without water).
  DemMethod(dem::Grains<D> grains, const dem::Params& params, std::vector<dem::Plane<D>> walls, const Vec<D>& gravity,
            double dt, double contact_step, std::optional<Simulator<D>> water);

  std::string_view name() const override { return "dem"; }
  /// Keeps the frame as the last good state; steps the SPH water (its step size is the step's),
  /// advances the grains over it in equal contact steps, then, with water, exchanges with it
  /// (dem::exchange_with_water: coupling forces, absorption, wetness propagation).
  double step() override;
  double time() const override { return time_; }
  long steps() const override { return steps_; }
  /// x, v, m (dry mass plus water held), phase (sand) of the grains, with the grain radius as
  /// support and the grain's mass over its volume as density; then the SPH particles' own fields.
  ParticleView<D> particles() const override { return view_of(frame_); }
  /// The contacts' count is their contact steps since the run started.
  std::vector<StageTime> stage_times() const override {
    return stage_times_of(dem::dem_stage_names, timers_, dem::DemStage::Contacts, contact_steps_);
  }
  void reset_stage_times() override {
    timers_.reset();
    contact_steps_ = 0;
  }
  std::optional<long> own_steps() const override { return contact_steps_; }

  const dem::Grains<D>& grains() const { return grains_; }
  const dem::Params& params() const { return params_; }
  /// The SPH water's particles (null in a run without water).
  const ParticleSet<D>* water() const { return water_ ? &water_->particles() : nullptr; }

 private:
  const DemFrame<D>& state() const override { return frame_; }
  ParticleView<D> view_of(const DemFrame<D>& f) const override;
  /// Advances the grains over dt in equal contact steps no longer than contact_step_.
  void step_grains(double dt);
  /// frame_ from the grains and the water.
  void refresh_frame();

  dem::Grains<D> grains_;
  dem::Params params_;
  std::vector<dem::Plane<D>> walls_;
  Vec<D> gravity_;
  double dt_, contact_step_;
  std::optional<Simulator<D>> water_;
  bool wet_;
  double time_ = 0.0;
  long steps_ = 0, contact_steps_ = 0;
  dem::Contacts<D> contacts_;
  dem::ExchangeGrids<D> exchange_;
  StageClock<dem::DemStage> timers_;
  DemFrame<D> frame_;
};

/// DEM at t = 0: each of the case's sand blocks packed by settling grains seeded at spacing dx
/// (radii drawn per block from a fixed seed) in a mould of the block, trimmed to its height, the
/// block's mass ρ V shared equally by its grains, each holding `moisture` of its capacity; the
/// case's water blocks as the SPH scene of the case without its sand (build_scene, Simulator).
template <int D>
std::unique_ptr<Method<D>> make_dem_method(const CaseSpec& spec, double dx);

}  // namespace sc
