// The seam between a simulation method and everything that runs or measures one.
//
// The runner, the bench, checkpoints and the observers of validation/ see a run only through
// Method<D>: it steps, tells its clock, shows its particles read-only (ParticleView), hashes its
// state, times its stages and writes its frames. SPH, Zhu-Bridson FLIP, DEM and two-grid MPM each
// implement it in their own folder; solver/method/registry.hpp builds the one a case names.
// What only one method can answer (SPH's neighbour lists, its porous parameters) lives behind that
// method's own probe, never in this interface.
#pragma once
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/types.hpp"
#include "io/json_reader.hpp"

namespace sc {

/// Read-only view of a method's particles, valid until its next step. Every method fills x, v, m
/// and phase; an optional field is empty when the method has no such quantity on its particles.
template <int D>
struct ParticleView {
  std::span<const Vec<D>> x;              ///< position [m]
  std::span<const Vec<D>> v;              ///< velocity [m/s]
  std::span<const double> m;              ///< mass the method moves [kg]
  std::span<const std::uint8_t> phase;    ///< Phase as an integer
  /// Stable identity (optional: a method that leaves it empty never reorders, adds or removes
  /// particles, so the index is the identity; see identity()).
  std::span<const std::int64_t> id;
  std::span<const double> pressure;       ///< [Pa] (optional)
  std::span<const double> density;        ///< [kg/m^3] (optional)
  std::span<const double> support;        ///< radius within which the particle interacts [m] (optional)
  std::span<const double> porosity;       ///< pore fraction of a porous particle, 0 elsewhere (optional)
  std::span<const double> held_water;     ///< water in a porous particle's pores, besides m [kg] (optional)
  std::span<const double> leaving_water;  ///< water that has left the pores and is about to become free water [kg] (optional)
  std::span<const double> saturation;     ///< water fraction of a porous particle's pores, in [0, 1] (optional)
  std::span<const double> pore_volume;    ///< volume of a porous particle's pores, 0 elsewhere [m^D] (optional)
  std::span<const double> pore_water_pressure;  ///< pressure of the water in the pores [Pa] (optional)

  std::size_t size() const { return x.size(); }
  /// The identity of particle i: its id, or its index for a method without ids.
  std::int64_t identity(std::size_t i) const { return id.empty() ? static_cast<std::int64_t>(i) : id[i]; }
  Phase phase_of(std::size_t i) const { return static_cast<Phase>(phase[i]); }
  bool moves(std::size_t i) const { return phase_of(i) != Phase::Boundary; }
  /// Water particle i holds besides its mass: in its pores and on its way out of them [kg].
  double water_held_by(std::size_t i) const {
    if (held_water.empty()) return 0.0;
    return leaving_water.empty() ? held_water[i] : held_water[i] + leaving_water[i];
  }
};

/// All water of a run [kg]: the mass of the water particles plus the water every other particle holds.
template <int D>
double total_water(const ParticleView<D>& view) {
  double sum = 0.0;
  for (std::size_t i = 0; i < view.size(); ++i) sum += view.phase_of(i) == Phase::Water ? view.m[i] : view.water_held_by(i);
  return sum;
}

/// Wall-clock seconds a method spent in one of its named stages since the run started (or the last
/// reset_stage_times), and the stage's work units where the method counts them (FLIP's projection:
/// conjugate-gradient iterations; DEM's contacts: contact steps; 0: not counted).
struct StageTime {
  std::string name;
  double seconds = 0.0;
  long count = 0;
};

template <int D>
class Method {
 public:
  virtual ~Method() = default;
  /// The registry name: "sph", "flip", "dem", "mpm".
  virtual std::string_view name() const = 0;
  /// Advances by one step and returns its size [s]. Throws BlowUpError on an invalid state, after
  /// which last_good_frame() shows the state at the start of the failed step.
  virtual double step() = 0;
  virtual double time() const = 0;
  virtual long steps() const = 0;
  virtual ParticleView<D> particles() const = 0;
  /// Hash of the state (positions and velocities, in a fixed order) as 16 hex digits: two runs
  /// agree bitwise exactly when their checksums do.
  virtual std::string checksum() const = 0;
  /// Exclusive stage times (every instant in one stage), in the method's own stage order.
  virtual std::vector<StageTime> stage_times() const = 0;
  virtual void reset_stage_times() = 0;
  /// The method's own time steps since the run started or the last reset_stage_times, for a method
  /// that takes several per case step (DEM's contact steps, MPM's steps); none for one whose step is
  /// the case step.
  virtual std::optional<long> own_steps() const { return std::nullopt; }
  /// The current particles as a VTU document (ParaView), every particle field a point array.
  virtual std::string vtu_frame() const = 0;
  /// The state at the start of the last step, as a VTU document (written after a blow-up).
  virtual std::string last_good_frame() const = 0;
  /// Whether the method can write a checkpoint that resumes bitwise (`run --checkpoint-every`,
  /// `--resume`); the registry tells the same for a method name before one is built.
  virtual bool writes_checkpoints() const = 0;
  /// Writes the current state to `path` (atomically) with `run`, the runner's bookkeeping (the
  /// frames it has written), which a resumed run gets back. Only when writes_checkpoints().
  virtual void write_checkpoint(const std::string& path, const json& run) const = 0;
};

}  // namespace sc
