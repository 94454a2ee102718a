#include "simulator/simulator.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "adaptive/density_blend.hpp"
#include "boundary/wall_pressure.hpp"
#include "porous/partial_water_pressure.hpp"
#include "porous/porous_flow.hpp"
#include "porous/porous_setup.hpp"
#include "sand/rigid_wall_contact.hpp"
#include "sand/sand_forces.hpp"
#include "simulator/symplectic_euler.hpp"
#include "scene/scene_builder.hpp"
#include "sph/density.hpp"
#include "water/viscosity_force.hpp"
#include "water/water_forces.hpp"

namespace sc {

SimulationParams SimulationParams::from_case(const CaseSpec& spec, double spacing) {
  SimulationParams p;
  p.dt_max = spec.dt_max;
  p.cfl = spec.cfl;
  p.density_window = spec.density_window;
  p.relax_until = spec.relax_until;
  p.relax_rate = spec.relax_rate;
  p.support_ratio = spec.support_ratio;
  p.eos = spec.eos;
  p.water = spec.water;
  p.sand = spec.sand;
  const Resolution res = resolve(spec, spacing);
  const double volume = std::pow(spacing, spec.dimension);
  p.water.reference_mass = spec.water.rest_density * volume;
  p.water.full_moment = spec.dimension == 2 ? full_moment<2>(spec.support_ratio, spec.water.density_kernel)
                                            : full_moment<3>(spec.support_ratio, spec.water.density_kernel);
  p.water.viscosity_moment = spec.dimension == 2 ? viscosity_moment<2>(spec.support_ratio, spec.water.density_kernel)
                                                 : viscosity_moment<3>(spec.support_ratio, spec.water.density_kernel);
  if (spec.artificial_viscosity > 0.0)  // ν = α h c / (2(D + 2)) (Monaghan 1992)
    p.water.viscosity = spec.artificial_viscosity * spec.water.rest_density * spec.support_ratio * spacing *
                        spec.eos.sound_speed / (2.0 * (spec.dimension + 2));
  p.gravity = spec.gravity;
  p.domain_min = spec.domain_min;
  p.domain_max = spec.domain_max;
  p.tank = spec.tank;
  p.tank_wall_thickness = res.wall_layers * spacing;
  if (spec.porous) {
    p.porous = *spec.porous;
    if (spec.dimension == 2)
      derive_porous<2>(*p.porous, spacing, res.h, res.water_mass, spec.water.density_kernel);
    else
      derive_porous<3>(*p.porous, spacing, res.h, res.water_mass, spec.water.density_kernel);
  }
  if (spec.adaptive) {
    p.adaptive = *spec.adaptive;
    const double finest_volume = res.water_mass / spec.water.rest_density;
    if (spec.dimension == 2)
      derive_adaptivity<2>(*p.adaptive, spacing, finest_volume);
    else
      derive_adaptivity<3>(*p.adaptive, spacing, finest_volume);
  }
  return p;
}

template <int D>
Simulator<D>::Simulator(ParticleSet<D> particles, SimulationParams params, std::optional<Comm> ranks)
    : ps_(std::move(particles)), params_(std::move(params)) {
  g_ = to_vec<D>(params_.gravity);
  lo_ = to_vec<D>(params_.domain_min);
  hi_ = to_vec<D>(params_.domain_max);
  for (std::size_t i = 0; i < ps_.size(); ++i) has_sand_ = has_sand_ || ps_.phase_of(i) == Phase::Sand;
  if (params_.tank && params_.tank->collision) tank_walls_ = TankWalls<D>::from_tank(*params_.tank, params_.tank_wall_thickness);
  last_dt_ = params_.dt_max;
  throw_first_error([&](std::size_t i) { return state_error(i); });  // the scene as built (before any scatter)
  if (!ranks || ranks->size() == 1) return;
  dd_.emplace(*ranks);
  dd_->scatter(ps_);
}

template <int D>
template <class Field>
void Simulator<D>::refresh_halo(Field& field) {
  if (!dd_) return;
  auto t = timers_.time(Stage::Halo);
  dd_->refresh(field);
}

template <int D>
typename Simulator<D>::MotionScales Simulator<D>::motion_scales() const {
  // Length scale: the particle spacing h_i / support_ratio, not the kernel support, so the limits
  // do not loosen when a case chooses a wider support. It is taken from the support, not from the
  // mass ((m/ρ0)^(1/D)): a water particle being absorbed keeps its support while its mass goes to
  // zero, and a mass-based spacing let one nearly empty particle collapse the step (dt → 1e-8 s in
  // wet_sand_collapse). Split and merged particles carry the support of their level.
  double hmin = INFINITY, vmax = 0.0, amax = g_.norm();
  const auto n = static_cast<std::int64_t>(ps_.size());
#pragma omp parallel for schedule(static) reduction(min : hmin) reduction(max : vmax, amax)  // exact: any threads
  for (std::int64_t i = 0; i < n; ++i) {
    if (!ps_.moves(i) || (dd_ && dd_->is_halo(i))) continue;
    hmin = std::min(hmin, ps_.h[i] / params_.support_ratio);
    vmax = std::max(vmax, ps_.v[i].norm());
    amax = std::max(amax, ps_.force[i].norm() / ps_.m[i]);
  }
  if (dd_) {  // over the ranks (exact: minima and maxima)
    std::array<double, 3> m = {-hmin, vmax, amax};
    dd_->comm().max(m);
    hmin = -m[0];
    vmax = m[1];
    amax = m[2];
  }
  return {hmin, vmax, amax};
}

template <int D>
double Simulator<D>::stable_dt() const {
  if (params_.cfl <= 0.0) return params_.dt_max;
  const MotionScales scales = motion_scales();
  const double hmin = scales.spacing;
  if (!std::isfinite(hmin)) return params_.dt_max;
  double dt = std::min(params_.dt_max, motion_limit(hmin, scales.speed, scales.acceleration));
  if (params_.water.viscosity > 0.0) {
    const double mu = params_.water.pair_viscosity(params_.water.viscosity);
    dt = std::min(dt, 0.125 * hmin * hmin * params_.water.rest_density / mu);
  }
  return dt;
}

template <int D>
double Simulator<D>::motion_limit(double spacing, double speed, double acceleration) const {
  const double cfl = params_.cfl * spacing / (params_.eos.sound_speed + speed);
  return acceleration > 0.0 ? std::min(cfl, 0.25 * std::sqrt(spacing / acceleration)) : cfl;
}

template <int D>
void Simulator<D>::compute_forces() {
  {
    auto t = timers_.time(Stage::Neighbours);
    find_neighbours();
  }
  {
    auto t = timers_.time(Stage::Density);
    compute_densities();
  }
  if (params_.adaptive && steps_ % params_.adaptive->interval == 0 && steps_ > 0) adapt();
  {
    auto t = timers_.time(Stage::Density);
    const auto n = static_cast<std::int64_t>(ps_.size());
    // Dynamic: the moving particles, the only ones with work, are stored first (a static split gave
    // them all to the first thread).
#pragma omp parallel for schedule(dynamic, 256)
    for (std::int64_t i = 0; i < n; ++i)
      if (ps_.moves(i)) ps_.p[i] = params_.eos.pressure(ps_.rho[i], ps_.rho0[i]);
    if (partial_water_mass() > 0.0) {
      refresh_halo(ps_.rho);  // the parcels' pressure reads the full neighbours' pressure and volume
      refresh_halo(ps_.p);
      set_partial_water_pressure(ps_, nb_, partial_water_mass());
      set_partial_water_density(ps_, partial_water_mass(), params_.porous->fluid_density);
    }
    refresh_halo(ps_.rho);  // the walls' pressure reads the moving neighbours'
    refresh_halo(ps_.p);
    extrapolate_wall_pressure(ps_, nb_, g_, params_.eos);
    refresh_halo(ps_.rho);  // the corrections and forces read the walls'
    refresh_halo(ps_.p);
  }
  {
    auto t = timers_.time(Stage::Forces);
    const auto n = static_cast<std::int64_t>(ps_.size());
#pragma omp parallel for schedule(static)
    for (std::int64_t i = 0; i < n; ++i) ps_.force[i] = ps_.moves(i) ? Vec<D>(ps_.m[i] * g_) : Vec<D>::Zero();
    if (params_.water.gradient_correction) {
      compute_gradient_corrections(ps_, nb_, CorrectionBand::of_full_moment(params_.water.full_moment), correction_);
      if (partial_water_mass() > 0.0) weight_partial_water_corrections(ps_, partial_water_mass(), correction_);
      refresh_halo(correction_);
    }
    add_water_forces(ps_, nb_, params_.water, correction_);
    if (has_sand_) compute_sand_forces();
    if (partial_water_mass() > 0.0)
      add_partial_water_wall_contact(ps_, nb_, params_.sand, params_.eos.sound_speed, last_dt_, partial_water_mass());
  }
}

template <int D>
double Simulator<D>::partial_water_mass() const {
  // One model of a partly absorbed water parcel in every porous scene, moving sand or a fixed bed,
  // adaptive or not: is_partial_water compares a particle with a full one at its own level, so a
  // split or merged particle is not a parcel (porous/partial_water_pressure.hpp).
  return params_.porous ? params_.porous->water_mass : 0.0;
}

template <int D>
void Simulator<D>::compute_densities() {
  compute_density(ps_, nb_, params_.water.density_kernel, params_.water.rest_density);
  if (params_.adaptive) add_density_offsets(ps_);
}

template <int D>
void Simulator<D>::sort_storage() {
  auto t = timers_.time(Stage::Neighbours);
  nb_.bin_moving(ps_);
  ps_.permute(nb_.storage_order());
  nb_.bin(ps_);
}

template <int D>
void Simulator<D>::find_neighbours() {
  nb_.bin_moving(ps_);  // a step moves no fixed wall particle
  nb_.list_only_first(dd_ ? dd_->own() : SIZE_MAX);  // the halo's own sums would be overwritten
  nb_.find_pairs(ps_);
}

template <int D>
void Simulator<D>::compute_sand_forces() {
  add_sand_forces(ps_, nb_, params_.sand, params_.water, params_.eos.sound_speed, last_dt_, correction_, wall_force_);
  add_water_sand_contact(ps_, nb_, params_.sand, params_.eos.sound_speed, last_dt_);
  refresh_halo(ps_.force);  // the yield test's predicted velocities read the neighbours' forces so far
  update_sand_state(ps_, nb_, params_.sand, g_.norm(), last_dt_, sand_stress_, predicted_velocity_,
                    params_.porous ? params_.porous->stress_scale : 0.0, params_.porous ? params_.porous->pore_stiffness : 0.0);
  refresh_halo(sand_stress_);  // the friction reads the neighbours' stress
  refresh_halo(ps_.rigid);     // the clusters join rigid neighbours
  const MatArray<D> uncorrected;  // both branches lvalues: the choice binds, it does not copy correction_
  add_frictional_forces(ps_, nb_, sand_stress_, params_.water.gradient_correction ? correction_ : uncorrected);
}

template <int D>
void Simulator<D>::integrate(double dt) {
  const auto n = static_cast<std::int64_t>(ps_.size());
  // Initial relaxation (a numerical device for cases that start from a lattice, not physics):
  // before relax_until, velocities decay at relax_rate so the start-up waves die out.
  const double damping = time_ < params_.relax_until ? std::exp(-params_.relax_rate * dt) : 1.0;
  if (has_sand_) {
    auto tc = timers_.time(Stage::Clusters);
    if (dd_) {
      motions_ = clusters_over_ranks_.motions(clusters_, dt, params_.sand.inertia, params_.sand.wall_mu());
    } else {
      // eqs 13-18, from the velocities before the step
      cluster_motions<D>(ps_, clusters_, dt, params_.sand.inertia, motions_, cluster_buffers_);
      constrain_clusters_by_walls<D>(ps_, nb_, clusters_, motions_, dt, params_.sand.wall_mu(), wall_contacts_);
    }
  }
  if (tank_walls_) x_start_.resize(ps_.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    if (!ps_.moves(i)) continue;
    if (tank_walls_) x_start_[i] = ps_.x[i];
    if (has_sand_ && ps_.cluster[i] != 0) continue;
    symplectic_euler_step<D>(ps_.x[i], ps_.v[i], ps_.force[i], ps_.m[i], dt, damping);
  }
  if (params_.adaptive) decay_density_offsets(ps_, dt, params_.adaptive->blend_time);
  if (has_sand_) move_clusters<D>(ps_, clusters_, motions_, dt, damping, cluster_buffers_);
  if (tank_walls_) collide_with_tank(ps_, *tank_walls_, x_start_);  // last line behind the wall particles
}

template <int D>
double Simulator<D>::step() {
  // Whatever the stages below leave untimed (the blow-up guard's copy and check, the step size,
  // the compaction) counts as integration: the stage timers are exclusive (core/stage_timers.hpp).
  auto t = timers_.time(Stage::Integration);
  ++revision_;
  if (dd_) {
    auto th = timers_.time(Stage::Halo);
    dd_->begin_step(ps_, steps_, steps_ % kSortEvery == 0);
    nb_.impose_bounds(dd_->bounds());
  } else if (steps_ % kSortEvery == 0) {
    sort_storage();
  }
  save_last_good();
  if (dd_) {
    auto th = timers_.time(Stage::Halo);
    dd_->add_halo(ps_);
  }
  compute_forces();
  const double dt = stable_dt();
  if (!(dt >= kShortestStepFraction * params_.dt_max)) {  // rare: the motion scales again
    const MotionScales scales = motion_scales();
    check([&](std::size_t i) { return runaway(i, scales); });
  }
  if (has_sand_) {
    {
      auto tf = timers_.time(Stage::Forces);
      add_wall_friction(ps_, wall_force_, params_.sand.wall_mu(), dt);
    }
    auto tc = timers_.time(Stage::Clusters);
    if (!params_.sand.rigid_clusters) clusters_.clear();
    else if (dd_) clusters_over_ranks_.find(ps_, nb_, *dd_, clusters_);
    else find_clusters(ps_, nb_, clusters_);
  }
  integrate(dt);
  last_dt_ = dt;
  if (params_.porous) {  // thesis Fig. 3.6 line 7: absorption and emission (solver/porous/)
    refresh_halo(ps_.x);  // the halo moved with forces from its partial neighbour lists
    refresh_halo(ps_.v);
    auto tp = timers_.time(Stage::Porous);
    porous_step(ps_, nb_, *params_.porous, g_, dt, porous_work_, dd_ ? &*dd_ : nullptr);
  }
  if (dd_) {
    auto th = timers_.time(Stage::Halo);
    dd_->compact(ps_, porous_work_.emitters);  // the additions' one-process order, from their emitters
  } else {
    ps_.compact();
  }
  check([&](std::size_t i) { return state_error(i); });
  guard_synced_ = true;
  time_ += dt;
  ++steps_;
  return dt;
}

template <int D>
void Simulator<D>::save_last_good() {
  if (dd_) dd_->save_last_good_keys();
  if (guard_synced_ && last_good_.layout() == ps_.layout())
    last_good_.refresh_from(ps_);
  else
    last_good_.copy_from(ps_);
}

template <int D>
void Simulator<D>::adapt() {
  auto t = timers_.time(Stage::Adaptive);
  if (dd_) {
    adapt_over_ranks();
  } else {
    adapt_particles<D>(ps_, nb_, *params_.adaptive, time_, adapt_account_);
    nb_.rebuild(ps_);
  }
  set_density_offsets(ps_, nb_, params_.water.density_kernel, params_.water.rest_density);
  refresh_halo(ps_.density_offset);
}

template <int D>
void Simulator<D>::adapt_over_ranks() {
  // The feature size is a function of the whole scene's surface, and the greedy pairing of merges
  // a sequence over the whole scene in storage order: every rank runs the one-process pass on the
  // whole scene (its own particles' densities are complete, the halo is left out), then keeps its
  // share of the result with a new halo.
  ParticleSet<D> whole = dd_->gather(ps_);
  NeighbourGrid<D> nb;
  nb.rebuild(whole);
  const AdaptChanges changes = adapt_particles<D>(whole, nb, *params_.adaptive, time_, adapt_account_);
  dd_->adopt(ps_, std::move(whole), changes.removed, changes.queued_by);
  nb_.impose_bounds(dd_->bounds());
  nb_.list_only_first(dd_->own());  // the new share's own particles (the halo's sums would be overwritten)
  nb_.rebuild(ps_);
}

template <int D>
std::optional<StateError> Simulator<D>::state_error(std::size_t i) const {
  if (!ps_.x[i].allFinite()) return StateError{"position", "not finite"};
  if (!ps_.v[i].allFinite()) return StateError{"velocity", "not finite"};
  if (!std::isfinite(ps_.rho[i]) || !std::isfinite(ps_.p[i])) return StateError{"density", "not finite"};
  for (int d = 0; d < D; ++d)
    if (ps_.x[i][d] < lo_[d] || ps_.x[i][d] > hi_[d]) return StateError{"position", "particle left the domain"};
  if (params_.density_window > 0.0 && ps_.moves(i) && steps_ > 0 &&
      std::abs(ps_.rho[i] / ps_.rho0[i] - 1.0) > params_.density_window)
    return StateError{"density", "outside the configured window |rho/rho0 - 1| <= " + std::to_string(params_.density_window)};
  return std::nullopt;
}

template <int D>
std::optional<StateError> Simulator<D>::runaway(std::size_t i, const MotionScales& scales) const {
  if (!ps_.moves(i) || (dd_ && dd_->is_halo(i))) return std::nullopt;
  const double speed = ps_.v[i].norm(), acceleration = ps_.force[i].norm() / ps_.m[i];
  const double limit = motion_limit(scales.spacing, speed, acceleration);
  if (limit >= kShortestStepFraction * params_.dt_max) return std::nullopt;
  const bool by_speed = limit == motion_limit(scales.spacing, speed, 0.0);
  return StateError{by_speed ? "velocity" : "force",
                    collapsed_step_reason(by_speed ? "a speed" : "an acceleration", by_speed ? speed : acceleration,
                                          by_speed ? "m/s" : "m/s^2", limit, params_.dt_max)};
}

template <int D>
template <class ErrorOf>
std::size_t Simulator<D>::first_error(ErrorOf error_of) const {
  const auto n = static_cast<std::int64_t>(ps_.size());
  std::int64_t first = n;  // the lowest offending index, whatever the number of threads
#pragma omp parallel for schedule(static) reduction(min : first)
  for (std::int64_t i = 0; i < n; ++i)
    if (i < first && error_of(i)) first = i;
  return static_cast<std::size_t>(first);
}

template <int D>
template <class ErrorOf>
void Simulator<D>::check(ErrorOf error_of) {
  try {
    if (dd_) throw_first_error_over_ranks(error_of);
    else throw_first_error(error_of);
  } catch (const BlowUpError&) {
    ps_ = last_good_;
    if (dd_) dd_->restore_last_good_keys();
    guard_synced_ = false;
    throw;
  }
}

template <int D>
template <class ErrorOf>
void Simulator<D>::throw_first_error(ErrorOf error_of) const {
  const std::size_t first = first_error(error_of);
  if (first == ps_.size()) return;
  const StateError e = *error_of(first);
  throw BlowUpError(steps_ + 1, time_, static_cast<long>(first), std::string(phase_name(ps_.phase_of(first))), e.field, e.what);
}

template <int D>
template <class ErrorOf>
void Simulator<D>::throw_first_error_over_ranks(ErrorOf error_of) const {
  const std::size_t n = ps_.size(), first = first_error(error_of);
  // Keys follow the index on each rank, and a key is the particle's index in the one-process run.
  std::array<std::uint64_t, 1> key = {first < n ? dd_->key(first) : UINT64_MAX};
  dd_->comm().min(key);
  if (key[0] == UINT64_MAX) return;
  const bool mine = first < n && dd_->key(first) == key[0];
  std::array<std::uint64_t, 1> root = {mine ? static_cast<std::uint64_t>(dd_->comm().rank()) : UINT64_MAX};
  dd_->comm().min(root);
  std::string what;
  if (mine) {
    const StateError e = *error_of(first);
    what = std::string(phase_name(ps_.phase_of(first))) + '\n' + e.field + '\n' + e.what;
  }
  what = dd_->comm().broadcast(what, static_cast<int>(root[0]));
  const std::size_t a = what.find('\n'), b = what.find('\n', a + 1);
  throw BlowUpError(steps_ + 1, time_, static_cast<long>(key[0]), what.substr(0, a), what.substr(a + 1, b - a - 1),
                    what.substr(b + 1));
}

template class Simulator<2>;
template class Simulator<3>;

}  // namespace sc
