// PIC/FLIP sand and water of Zhu & Bridson 2005, "Animating Sand as a Fluid", in 2-D and 3-D:
// particles carry position, velocity, mass and phase; every step transfers them to a MAC grid, adds
// gravity, projects (free surface p = 0, static tank walls), runs the sand step on sand cells,
// extends the velocity into the air, updates the particles (PIC for sand, FLIP blend for water) and
// moves them (RK2).
#pragma once
#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include "core/stage_timers.hpp"
#include "flip/pressure.hpp"
#include "flip/sand_step.hpp"
#include "flip/transfer.hpp"

namespace sc::flip {

/// The stages of a step, in order: particles to grid (with gravity), pressure projection, the
/// frictional sand stress and wall friction, rigid groups, and extrapolation, grid to particles and
/// advection.
enum class FlipStage { Transfer, Projection, SandStress, RigidGroups, Advection, Count };

inline constexpr std::array<std::string_view, static_cast<std::size_t>(FlipStage::Count)> flip_stage_names = {
    "transfer", "projection", "sand stress", "rigid groups", "advection"};

template <std::size_t N>
constexpr std::array<bool, N> filled(bool value) {
  std::array<bool, N> a{};
  a.fill(value);
  return a;
}

template <int D>
struct FlipParams {
  Vec<D> tank_lo = Vec<D>::Zero();
  Vec<D> tank_hi = Vec<D>::Ones();
  double dx = 0.01;                                     ///< grid cell width [m]
  Vec<D> gravity = -9.81 * Vec<D>::Unit(D - 1);         ///< [m/s^2]
  double water_density = 1000.0;                       ///< [kg/m^3]
  SandParams sand;                                      ///< sand density, φ, c, wall friction, yield surface
  std::array<bool, 2 * D> rough_side = filled<2 * D>(true);  ///< sides (2a + upper) whose wall friction acts on sand
  double flip_ratio = 0.95;                             ///< FLIP share of water's velocity update (sand: PIC)
  double cfl = 1.0;                                     ///< particles move at most cfl·Δx per step
  double dt_max = 1e-3;                                 ///< [s]
  double cg_tolerance = 1e-12;                          ///< relative residual of the pressure solve
  long cg_max_iterations = 2000;
  int extrapolation_layers = 3;                         ///< cell widths the velocity is extended into air
};

/// The particles of the method, laid out as ParticleView<D> (solver/method/method.hpp) expects.
template <int D>
struct FlipParticles {
  VecArrayOf<D> x, v;              ///< position [m], velocity [m/s]
  std::vector<double> m;           ///< mass [kg]
  std::vector<std::uint8_t> phase; ///< Phase::Water or Phase::Sand as an integer

  std::size_t size() const { return x.size(); }
  bool is_sand(std::size_t i) const { return phase[i] == static_cast<std::uint8_t>(Phase::Sand); }
};

/// Fills the box [lo, hi] with particles on the lattice of the given spacing (one at the centre of
/// each lattice cell), each moved by up to ±jitter/2 of the spacing per axis and of mass ρ spacing^D,
/// at rest. Deterministic in `seed`.
template <int D>
void seed_lattice(const Vec<D>& lo, const Vec<D>& hi, double spacing, Phase phase, double density, double jitter,
                  unsigned seed, FlipParticles<D>& ps);

/// Fills the box [lo, hi] (whole cells of `grid`) with 2^D particles per cell, one in each cell of
/// the 2x2(x2) sub-grid jittered by up to ±jitter/2 of a sub-cell [Zhu-Bridson 2005: Initializing
/// Particles] (8 per cell in 3-D, 4 in 2-D), each of mass ρ Δx^D / 2^D, at rest. Deterministic in
/// `seed`.
template <int D>
void seed_box(const MacGrid<D>& grid, const Vec<D>& lo, const Vec<D>& hi, Phase phase, double density, double jitter,
              unsigned seed, FlipParticles<D>& ps);

template <int D>
class FlipSolver {
 public:
  FlipSolver(const FlipParams<D>& params, FlipParticles<D> particles);

  /// One step [Zhu-Bridson 2005: Simulation algorithm]; returns Δt [s]. Throws BlowUpError when a
  /// particle's position or velocity is no longer finite, the pressure solve fails, or Δt falls
  /// below kShortestStepFraction of dt_max (core/errors.hpp collapsed_step; checked first).
  double step();
  /// Δt of the next step: cfl·Δx over the fastest particle, at most dt_max.
  double next_dt() const;

  double time() const { return time_; }
  long steps() const { return steps_; }
  const FlipParticles<D>& particles() const { return ps_; }
  const FlipParams<D>& params() const { return params_; }
  const MacGrid<D>& grid() const { return grid_; }
  /// The grid state of the last step: face velocities, cell labels and densities, pressure [Pa].
  const FaceField<D>& velocity() const { return u_; }
  const CellState<D>& cells() const { return cells_; }
  const std::vector<double>& pressure() const { return p_; }
  const ProjectionStats& projection_stats() const { return stats_; }
  /// Wall-clock seconds spent in each FlipStage since the start (or the last reset()).
  StageClock<FlipStage>& timers() { return timers_; }
  const StageClock<FlipStage>& timers() const { return timers_; }

 private:
  void transfer_to_grid();
  void sand_step(double dt, const FaceField<D>& before_projection);
  void update_particles(double dt);

  FlipParams<D> params_;
  FlipParticles<D> ps_;
  MacGrid<D> grid_;
  std::vector<double> radius_;  ///< per particle half its spacing (m/ρ)^(1/D), for the surface distance
  ParticleBins<D> bins_;
  FaceField<D> u_, u_old_, weight_;
  bool flip_water_;  ///< whether some water particle takes a FLIP share: only then is u_old_ kept and extended
  FaceField<D> u_before_projection_;  ///< u after gravity, for the wall friction (kept: no reallocation per step)
  CellState<D> cells_;
  SandCells<D> sand_;
  std::vector<double> p_;
  ProjectionStats stats_;
  double time_ = 0.0;
  long steps_ = 0;
  StageClock<FlipStage> timers_;
};

}  // namespace sc::flip
