// The simulator: one step reads top to bottom like the thesis algorithm (thesis Fig. 3.9), each
// line a call into one physics file. Later physics (sand, porous flow, adaptivity) plugs in here.
#pragma once
#include <optional>
#include <string>

#include "boundary/wall_collision.hpp"
#include "core/errors.hpp"
#include "core/particle_set.hpp"
#include "core/stage_timers.hpp"
#include "case/case_file.hpp"
#include "neighbours/neighbour_grid.hpp"
#include "parallel/decomposition.hpp"
#include "porous/porous_flow.hpp"
#include "sand/clusters.hpp"
#include "sand/clusters_over_ranks.hpp"
#include "sand/sand_forces.hpp"
#include "sph/gradient_correction.hpp"

namespace sc {

struct SimulationParams {
  double dt_max = 0.001;      ///< [s] fixed step, or the cap of the CFL step
  double cfl = 0.0;           ///< 0 = fixed step
  double density_window = 0;  ///< blow-up guard on |ρ/ρ0 − 1| (0 = off)
  double relax_until = 0.0;   ///< [s] initial relaxation: velocities damped before this time
  double relax_rate = 0.0;    ///< [1/s] damping rate of the relaxation (v *= exp(−rate dt))
  double support_ratio = 2.0; ///< kernel support h / particle spacing: the step limits' length is h_i / ratio
  EquationOfState eos;
  WaterParams water;
  SandParams sand;
  std::optional<PorousParams> porous;  ///< porous flow (solver/porous/), derived for the case spacing
  std::optional<AdaptivitySpec> adaptive;  ///< split and merge (solver/adaptive/), derived for the spacing
  std::vector<double> gravity, domain_min, domain_max;
  std::optional<TankSpec> tank;      ///< the case's box tank: its closed sides also stop particles by collision
  double tank_wall_thickness = 0.0;  ///< [m] thickness of the tank's wall-particle layers at this spacing

  static SimulationParams from_case(const CaseSpec& spec, double spacing);
};

/// An invalid particle state: the field and what is wrong with it.
struct StateError {
  const char* field;
  std::string what;
};

template <int D>
class Simulator {
 public:
  /// `particles`: the whole scene. With `ranks` of more than one rank, the scene is decomposed over
  /// them (parallel/decomposition.hpp): every rank passes the same scene and keeps its share, and
  /// the run is bitwise the one-process run. Decomposed: every SPH scene (water, dry and wet sand,
  /// walls, porous flow, adaptive sampling); other methods are refused by the caller first
  /// (check_decomposable in method/registry.hpp).
  Simulator(ParticleSet<D> particles, SimulationParams params, std::optional<Comm> ranks = std::nullopt);

  /// Advances by one step; returns the step size used. Throws BlowUpError if the new state is
  /// invalid; the particles then still hold the last good state (see last_good()).
  double step();
  /// Step size for the current state: dt_max, or the CFL, force and viscous limits when cfl > 0.
  double stable_dt() const;

  /// The particles of this rank (all of them in one process; decomposed, this rank's own, without
  /// halo, between steps).
  const ParticleSet<D>& particles() const { return ps_; }
  /// Mutable access: the next step copies the whole state for its blow-up guard (not only what a
  /// step changes), so changes made through it must be made before that step.
  ParticleSet<D>& particles() {
    guard_synced_ = false;
    ++revision_;
    return ps_;
  }
  /// The state at the start of the last step (the blow-up guard's copy).
  const ParticleSet<D>& last_good() const { return last_good_; }
  const NeighbourGrid<D>& neighbours() const { return nb_; }
  const SimulationParams& params() const { return params_; }
  const Vec<D>& gravity() const { return g_; }
  double time() const { return time_; }
  long steps() const { return steps_; }
  void set_clock(double time, long steps) { time_ = time; steps_ = steps; }
  /// The previous step size: carried state a checkpoint must hold to resume bitwise.
  double last_dt() const { return last_dt_; }
  void set_last_dt(double dt) { last_dt_ = dt; }
  StageTimers& timers() { return timers_; }
  const StageTimers& timers() const { return timers_; }
  /// What adaptivity did so far in this run (zero when the case has no "adaptive" section).
  const AdaptAccount& adapt_account() const { return adapt_account_; }
  /// The decomposition over MPI ranks; null in one process.
  const Decomposition<D>* decomposition() const { return dd_ ? &*dd_ : nullptr; }
  /// Decomposed runs: rigid clusters with members on more than one rank, summed over the steps.
  long clusters_across_ranks() const { return clusters_over_ranks_.across_ranks(); }
  /// Changes whenever the particles may have changed (a step, mutable access).
  long revision() const { return revision_; }

 private:
  void compute_forces();
  /// Density of every moving particle: summation (eq 6) plus, in adaptive runs, the particle's
  /// decaying density offset (solver/adaptive/density_blend.hpp).
  void compute_densities();
  /// Mass m0 of a full water particle of level 0 in a porous scene, whose water particles lighter
  /// than a full one at their level are parcels of the exchange (is_partial_water), else 0.
  double partial_water_mass() const;
  /// Every kSortEvery steps (counted from the run's start, so a resumed run sorts at the same
  /// steps), at the start of the step, before the blow-up guard keeps the state: particles that are
  /// neighbours in space are put back next to each other in storage (NeighbourGrid::storage_order).
  /// A sort only relabels them (ParticleSet::permute, ids kept). Decomposed, the ranks sort at the
  /// same point (Decomposition::begin_step), so a last good state is in the one-process order.
  void sort_storage();
  /// Neighbour lists of the current step.
  void find_neighbours();
  static constexpr long kSortEvery = 16;
  /// Sand (thesis Fig. 3.3): yield state and frictional stress, then the sand forces.
  void compute_sand_forces();
  void integrate(double dt);
  /// Split and merge (thesis §3.6) when a pass is due (every params.adaptive->interval steps),
  /// after the densities of the step: rebuilds the neighbour lists for the new particles and
  /// sets the density offsets so that no particle's density jumps.
  void adapt();
  /// adapt() over MPI ranks: the pass on the gathered whole scene, then this rank's share of it.
  void adapt_over_ranks();
  /// If `error_of` (particle index → std::optional<StateError>) finds a particle wrong: puts the
  /// last good state back and throws BlowUpError naming the first one (lowest index; decomposed:
  /// lowest key, its index in the one-process run, on every rank).
  template <class ErrorOf>
  void check(ErrorOf error_of);
  template <class ErrorOf>
  void throw_first_error(ErrorOf error_of) const;
  template <class ErrorOf>
  void throw_first_error_over_ranks(ErrorOf error_of) const;
  /// The lowest index of a particle that `error_of` finds wrong (size() if none).
  template <class ErrorOf>
  std::size_t first_error(ErrorOf error_of) const;
  /// Overwrites the halo's values of `field` with their owners' (decomposed runs; else nothing).
  template <class Field>
  void refresh_halo(Field& field);
  /// What is wrong with particle i, if anything: a field not finite, a position outside the domain,
  /// a density outside the window.
  std::optional<StateError> state_error(std::size_t i) const;

  /// The smallest spacing and the largest speed and acceleration of the moving particles (over the
  /// ranks, exact): what the CFL and force conditions of the step size read.
  struct MotionScales {
    double spacing = INFINITY, speed = 0.0, acceleration = 0.0;
  };
  MotionScales motion_scales() const;
  /// The longest step that the CFL and force conditions allow a particle of this spacing, speed
  /// and acceleration.
  double motion_limit(double spacing, double speed, double acceleration) const;
  /// What is wrong with particle i when the motion limit of `scales` is below kShortestStepFraction
  /// of dt_max (core/errors.hpp): a speed or acceleration of its own that, at the smallest spacing,
  /// shrinks the step that far (speeds or forces running away: the run would stall, not stop).
  std::optional<StateError> runaway(std::size_t i, const MotionScales& scales) const;

  /// last_good_ ← ps_ at the start of a step: only what a step can change (refresh_from) when
  /// last_good_ holds the start of the previous step and nothing but that step changed ps_ since;
  /// over ranks, the decomposition keeps its keys alike.
  void save_last_good();

  ParticleSet<D> ps_, last_good_;
  bool guard_synced_ = false;  // last_good_ is the start of the previous step, ps_ its end
  NeighbourGrid<D> nb_;
  MatArray<D> correction_;  // kernel-gradient corrections of the current step
  MatArray<D> sand_stress_;   // tension-positive frictional stress −σ_f of each sand particle (eq 8)
  VecArrayOf<D> predicted_velocity_;  // v* of the yield test (update_sand_state)
  VecArrayOf<D> wall_force_;  // push of rough walls on each sand particle (normal of the wall friction)
  std::optional<TankWalls<D>> tank_walls_;  // closed sides of the case's tank (collision planes)
  VecArrayOf<D> x_start_;     // positions of the moving particles before the step's move (the collision's path start)
  PorousWork<D> porous_work_;  // buffers of the porous step
  Clusters clusters_;         // rigid sand clusters of the current step (decomposed: of clusters_over_ranks_'s particles)
  std::vector<ClusterMotion<D>> motions_;  // the clusters' rigid motions of the current step
  ClusterBuffers<D> cluster_buffers_;      // buffers of the clusters' motions and moves
  WallContactBuffers<D> wall_contacts_;    // buffers of the clusters' wall contacts
  ClustersOverRanks<D> clusters_over_ranks_;  // decomposed runs: the clusters of the whole scene
  bool has_sand_ = false;
  double last_dt_ = 0.0;      // step size of the previous step (the rigid stress, eq 12a, needs one)
  SimulationParams params_;
  Vec<D> g_, lo_, hi_;
  double time_ = 0.0;
  long steps_ = 0;
  StageTimers timers_;
  AdaptAccount adapt_account_;
  std::optional<Decomposition<D>> dd_;
  long revision_ = 0;
};

}  // namespace sc
