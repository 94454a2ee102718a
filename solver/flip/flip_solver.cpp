#include "flip/flip_solver.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "core/errors.hpp"
#include "core/particle_set.hpp"
#include "flip/extrapolate.hpp"

namespace sc::flip {

template <int D>
void seed_lattice(const Vec<D>& lo, const Vec<D>& hi, double spacing, Phase phase, double density, double jitter,
                  unsigned seed, FlipParticles<D>& ps) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(-0.5, 0.5);
  Index<D> dims{};
  for (int d = 0; d < D; ++d) dims[d] = static_cast<int>(std::lround((hi[d] - lo[d]) / spacing));
  const double mass = density * std::pow(spacing, D);
  for (std::size_t k = 0; k < MacGrid<D>::count(dims); ++k) {
    const Index<D> s = MacGrid<D>::unflat(k, dims);
    Vec<D> x;
    for (int d = 0; d < D; ++d) x[d] = lo[d] + (s[d] + 0.5 + jitter * uniform(rng)) * spacing;
    ps.x.push_back(x);
    ps.v.push_back(Vec<D>::Zero());
    ps.m.push_back(mass);
    ps.phase.push_back(static_cast<std::uint8_t>(phase));
  }
}

template <int D>
void seed_box(const MacGrid<D>& grid, const Vec<D>& lo, const Vec<D>& hi, Phase phase, double density, double jitter,
              unsigned seed, FlipParticles<D>& ps) {
  seed_lattice<D>(lo, hi, 0.5 * grid.dx, phase, density, jitter, seed, ps);
}

template <int D>
FlipSolver<D>::FlipSolver(const FlipParams<D>& params, FlipParticles<D> particles)
    : params_(params), ps_(std::move(particles)), grid_(params.tank_lo, params.tank_hi, params.dx), radius_(ps_.size()),
      flip_water_(params.flip_ratio > 0.0 && std::ranges::any_of(ps_.phase, [](std::uint8_t phase) {
                    return phase != static_cast<std::uint8_t>(Phase::Sand);
                  })) {
  for (std::size_t i = 0; i < ps_.size(); ++i)
    radius_[i] = 0.5 * particle_size<D>(ps_.m[i] / (ps_.is_sand(i) ? params_.sand.rest_density : params_.water_density));
}

template <int D>
double FlipSolver<D>::next_dt() const {
  double vmax = 0.0;
  for (const auto& v : ps_.v) vmax = std::max(vmax, v.norm());
  return vmax > 0.0 ? std::min(params_.dt_max, params_.cfl * grid_.dx / vmax) : params_.dt_max;
}

template <int D>
void FlipSolver<D>::transfer_to_grid() {
  bins_.build(grid_, ps_.x);
  particles_to_grid<D>(grid_, bins_, ps_.x, ps_.v, ps_.m, u_, weight_);
  cells_.label = label_cells<D>(grid_, bins_, ps_.m, ps_.phase);
  cells_.air_distance = air_distance<D>(grid_, bins_, ps_.x, radius_, cells_.label);
  cells_.density.assign(grid_.cell_count(), 0.0);
  const long cells = static_cast<long>(cells_.label.size());
#pragma omp parallel for schedule(static)
  for (long c = 0; c < cells; ++c)
    if (is_fluid(cells_.label[c]))
      cells_.density[c] = cells_.label[c] == Cell::Sand ? params_.sand.rest_density : params_.water_density;
  if (flip_water_) u_old_ = u_;
}

template <int D>
void FlipSolver<D>::sand_step(double dt, const FaceField<D>& before_projection) {
  auto stress_scope = timers_.time(FlipStage::SandStress);
  classify_sand<D>(grid_, cells_, u_, p_, params_.sand, dt, sand_);
  const SandCells<D>& sand = sand_;
  apply_frictional_stress<D>(grid_, cells_, sand, dt, u_);
  SideFriction<D> mu{};
  for (std::size_t side = 0; side < mu.size(); ++side) mu[side] = params_.rough_side[side] ? params_.sand.wall_mu() : 0.0;
  wall_friction<D>(grid_, cells_, sand, p_, before_projection, mu, dt, u_);
  auto rigid_scope = timers_.time(FlipStage::RigidGroups);
  for (const auto& group : rigid_groups<D>(grid_, sand.rigid)) {
    Vec<D> centre = Vec<D>::Zero();
    for (const auto k : group) centre += grid_.cell_centre(MacGrid<D>::unflat(k, grid_.n));
    centre /= static_cast<double>(group.size());
    const std::vector<GroupFace> faces = group_faces<D>(grid_, cells_, group);
    RigidFit<D> fit = fit_rigid_motion<D>(grid_, faces, centre, u_);
    group_wall_friction<D>(grid_, group, faces, fit_rigid_motion<D>(grid_, faces, centre, before_projection), mu, fit);
    apply_rigid_motion<D>(grid_, faces, fit, u_);
  }
}

template <int D>
void FlipSolver<D>::update_particles(double dt) {
  const long n = static_cast<long>(ps_.size());
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) {
    Vec<D> pic;
    if (ps_.is_sand(static_cast<std::size_t>(i)) || !flip_water_) {  // PIC: the grid's velocity
      pic = ps_.v[i] = grid_.velocity_at(u_, ps_.x[i]);
    } else {
      const auto [now, old] = grid_.velocities_at(u_, u_old_, ps_.x[i]);
      pic = now;
      ps_.v[i] = grid_to_particle<D>(now, old, ps_.v[i], params_.flip_ratio);
    }
    ps_.x[i] = advect_rk2<D>(grid_, u_, ps_.x[i], pic, dt);
  }
  for (std::size_t i = 0; i < ps_.size(); ++i)
    if (!ps_.x[i].allFinite() || !ps_.v[i].allFinite())
      throw BlowUpError(steps_ + 1, time_, static_cast<long>(i), ps_.is_sand(i) ? "sand" : "water",
                        ps_.x[i].allFinite() ? "v" : "x", "not finite");
}

template <int D>
double FlipSolver<D>::step() {
  const double dt = next_dt();
  if (!(dt >= kShortestStepFraction * params_.dt_max)) {
    throw collapsed_step(steps_ + 1, time_, ps_.v, [&](long i) { return ps_.is_sand(i); }, dt, params_.dt_max);
  }
  {
    auto scope = timers_.time(FlipStage::Transfer);
    transfer_to_grid();
    for (int a = 0; a < D; ++a) {  // gravity on every face that received particle mass
      const long faces = static_cast<long>(u_[a].size());
#pragma omp parallel for schedule(static)
      for (long k = 0; k < faces; ++k)
        if (weight_[a][k] > 0.0) u_[a][k] += params_.gravity[a] * dt;
    }
    u_before_projection_ = u_;
  }
  {
    auto scope = timers_.time(FlipStage::Projection);
    try {
      stats_ = project<D>(grid_, cells_, dt, params_.cg_tolerance, params_.cg_max_iterations, u_, p_);
    } catch (const std::runtime_error& e) {
      throw BlowUpError(steps_ + 1, time_, -1, "grid", "pressure", e.what());
    }
  }
  sand_step(dt, u_before_projection_);
  {
    auto scope = timers_.time(FlipStage::Advection);
    FaceField<D>* const fields[] = {&u_, &u_old_};
    extrapolate<D>(grid_, cells_.label, params_.extrapolation_layers, std::span(fields, flip_water_ ? 2 : 1));
    update_particles(dt);
  }
  time_ += dt;
  ++steps_;
  return dt;
}

template void seed_lattice<2>(const Vec<2>&, const Vec<2>&, double, Phase, double, double, unsigned,
                              FlipParticles<2>&);
template void seed_lattice<3>(const Vec<3>&, const Vec<3>&, double, Phase, double, double, unsigned,
                              FlipParticles<3>&);
template void seed_box<2>(const MacGrid<2>&, const Vec<2>&, const Vec<2>&, Phase, double, double, unsigned,
                          FlipParticles<2>&);
template void seed_box<3>(const MacGrid<3>&, const Vec<3>&, const Vec<3>&, Phase, double, double, unsigned,
                          FlipParticles<3>&);
template class FlipSolver<2>;
template class FlipSolver<3>;

}  // namespace sc::flip
