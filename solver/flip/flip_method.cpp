#include "flip/flip_method.hpp"

#include <cmath>

#include "scene/scene_builder.hpp"

namespace sc {

namespace {

/// Whole cells of width h in `extent`; -1 when it is not a whole number (relative 1e-9).
long whole_cells(double extent, double h) {
  const double n = extent / h;
  return std::abs(n - std::round(n)) <= 1e-9 * std::max(1.0, n) ? std::lround(n) : -1;
}

}  // namespace

FlipCaseParams read_flip_params(const CaseSpec& spec) {
  const json own = own_parameters(spec, "flip", "FLIP");
  JsonObject o(own, "/methods/flip", spec.file);
  FlipCaseParams p;
  p.cell_size = o.in_range("cell_size", 1.0, 4.0, false, p.cell_size);
  p.flip_ratio = o.in_range("flip_ratio", 0.0, 1.0, false, p.flip_ratio);
  p.cfl = o.in_range("cfl", 0.0, 5.0, true, p.cfl);
  p.cg_tolerance = o.in_range("cg_tolerance", 0.0, 1e-3, true, p.cg_tolerance);
  p.cg_max_iterations = o.integer("cg_max_iterations", 1, 1000000, p.cg_max_iterations);
  p.jitter = o.in_range("jitter", 0.0, 1.0, false, p.jitter);
  o.finish();
  check_tank_scene(spec, "flip", "its walls are the grid's", "has no porous flow");
  for (std::size_t b = 0; b < spec.blocks.size(); ++b)
    if (spec.blocks[b].fill == BlockFill::PorousBed)
      throw InputError(spec.file, "/blocks/" + std::to_string(b) + "/phase",
                       "method \"flip\" runs water and sand blocks only, not a porous bed");
  return p;
}

template <int D>
flip::FlipParams<D> flip_params(const CaseSpec& spec, const FlipCaseParams& own, double dx) {
  const TankSpec& tank = *spec.tank;
  const double h = own.cell_size * dx;
  flip::FlipParams<D> p;
  for (int d = 0; d < D; ++d) {
    const bool lo_wall = tank.closed(d, -1), hi_wall = tank.closed(d, 1);
    p.rough_side[2 * d] = tank.rule(d, -1) == WallRule::NoSlip;
    p.rough_side[2 * d + 1] = tank.rule(d, 1) == WallRule::NoSlip;
    if (lo_wall && hi_wall) {
      const long n = whole_cells(tank.max[d] - tank.min[d], h);
      if (n < 2)
        throw InputError(spec.file, "/methods/flip/cell_size",
                         "the tank's extent along " + std::string(1, "xyz"[d]) + " (" +
                             json(tank.max[d] - tank.min[d]).dump() +
                             " m) must be a whole number (at least 2) of cells of cell_size x spacing = " +
                             json(h).dump() + " m");
      p.tank_lo[d] = tank.min[d];
      p.tank_hi[d] = tank.max[d];
    } else if (hi_wall) {  // open below: whole cells down past the domain's edge
      p.tank_hi[d] = tank.max[d];
      p.tank_lo[d] = tank.max[d] - std::max(2.0, std::ceil((tank.max[d] - spec.domain_min[d]) / h - 1e-9)) * h;
    } else {  // open above (or on both sides): whole cells up past the domain's edge
      p.tank_lo[d] = lo_wall ? tank.min[d] : spec.domain_min[d];
      p.tank_hi[d] = p.tank_lo[d] + std::max(2.0, std::ceil((spec.domain_max[d] - p.tank_lo[d]) / h - 1e-9)) * h;
    }
  }
  p.dx = h;
  p.gravity = to_vec<D>(spec.gravity);
  p.water_density = spec.water.rest_density;
  p.sand = spec.sand;
  p.flip_ratio = own.flip_ratio;
  p.cfl = own.cfl;
  p.dt_max = spec.dt_max;
  p.cg_tolerance = own.cg_tolerance;
  p.cg_max_iterations = own.cg_max_iterations;
  return p;
}

template <int D>
FlipMethod<D>::FlipMethod(flip::FlipSolver<D> solver)
    : ParticleAdapter<D, flip::FlipParticles<D>>(solver.particles()), solver_(std::move(solver)) {}

template <int D>
double FlipMethod<D>::step() {
  this->keep_last_good();
  const double dt = solver_.step();
  projection_iterations_ += solver_.projection_stats().iterations;
  return dt;
}

template <int D>
ParticleView<D> FlipMethod<D>::view_of(const flip::FlipParticles<D>& ps) const {
  ParticleView<D> view = this->motion(ps);
  view.m = ps.m;
  view.phase = ps.phase;
  return view;
}

template <int D>
ParticleView<D> FlipMethod<D>::particles() const {
  const flip::FlipParticles<D>& ps = solver_.particles();
  const flip::FlipParams<D>& params = solver_.params();
  const bool have_pressure = solver_.pressure().size() == solver_.grid().cell_count();
  pressure_.resize(ps.size());
  density_.resize(ps.size());
  support_.assign(ps.size(), solver_.grid().dx);
  const std::vector<double> p =
      have_pressure ? flip::ghost_pressure<D>(solver_.grid(), solver_.cells(), solver_.pressure()) : std::vector<double>{};
  for (std::size_t i = 0; i < ps.size(); ++i) {
    pressure_[i] = have_pressure ? solver_.grid().interpolate_cells(p, ps.x[i]) : 0.0;
    density_[i] = ps.is_sand(i) ? params.sand.rest_density : params.water_density;
  }
  ParticleView<D> view = view_of(ps);
  view.pressure = pressure_;
  view.density = density_;
  view.support = support_;
  return view;
}

template <int D>
std::unique_ptr<Method<D>> make_flip_method(const CaseSpec& spec, double dx) {
  const FlipCaseParams own = read_flip_params(spec);
  const flip::FlipParams<D> params = flip_params<D>(spec, own, dx);
  check_blocks_inside<D>(spec, "flip", "the grid", params.tank_lo, params.tank_hi);
  flip::FlipParticles<D> ps;
  for (std::size_t b = 0; b < spec.blocks.size(); ++b) {
    const BlockSpec& block = spec.blocks[b];
    const double rho = block.fill == BlockFill::Sand ? spec.sand.rest_density : spec.water.rest_density;
    flip::seed_lattice<D>(to_vec<D>(block.min), to_vec<D>(block.max), dx, block.phase(), rho, own.jitter,
                          static_cast<unsigned>(b + 1), ps);
  }
  return std::make_unique<FlipMethod<D>>(flip::FlipSolver<D>(params, std::move(ps)));
}

template flip::FlipParams<2> flip_params<2>(const CaseSpec&, const FlipCaseParams&, double);
template flip::FlipParams<3> flip_params<3>(const CaseSpec&, const FlipCaseParams&, double);
template class FlipMethod<2>;
template class FlipMethod<3>;
template std::unique_ptr<Method<2>> make_flip_method<2>(const CaseSpec&, double);
template std::unique_ptr<Method<3>> make_flip_method<3>(const CaseSpec&, double);

}  // namespace sc
