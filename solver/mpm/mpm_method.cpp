#include "mpm/mpm_method.hpp"

#include <algorithm>
#include <cmath>

#include "core/errors.hpp"
#include "mpm/exchange.hpp"
#include "mpm/grid_field.hpp"
#include "scene/scene_builder.hpp"

namespace sc {

namespace {

/// Ghost node layers beyond each wall: a particle on a wall still has its whole stencil on the grid.
constexpr long ghost_layers = 2;

/// Whether the case has a block of this fill.
bool has_fill(const CaseSpec& spec, BlockFill fill) {
  for (const BlockSpec& b : spec.blocks)
    if (b.fill == fill) return true;
  return false;
}

/// The particles of one block on the lattice of spacing dx, each ρ dx^D of phase `phase`; water in
/// pores of porosity `porosity` (1: open water) takes the share `fill` of each site's volume.
template <int D>
void seed_block(const BlockSpec& block, double dx, double rho, Phase phase, mpm::Particles<D>& ps,
                double porosity = 1.0, double fill = 1.0) {
  std::array<long, D> n{};
  long count = 1;
  for (int d = 0; d < D; ++d) {
    n[d] = std::lround((block.max[d] - block.min[d]) / dx);
    count *= n[d];
  }
  const double volume = fill * std::pow(dx, D);
  for (long k = 0; k < count; ++k) {
    Vec<D> x;
    long rest = k;
    for (int d = 0; d < D; ++d) {
      x[d] = block.min[d] + (static_cast<double>(rest % n[d]) + 0.5) * dx;
      rest /= n[d];
    }
    ps.add(x, rho * volume, volume, phase, porosity);
  }
}

}  // namespace

MpmCaseParams read_mpm_params(const CaseSpec& spec) {
  const json own = own_parameters(spec, "mpm", "MPM");
  JsonObject o(own, "/methods/mpm", spec.file);
  MpmCaseParams p;
  p.cell_size = o.in_range("cell_size", 1.0, 4.0, false, p.cell_size);
  p.cfl = o.in_range("cfl", 0.0, 1.0, false, p.cfl);
  if (p.cfl <= 0.0) o.fail("cfl", "must be in (0, 1]");
  p.youngs_modulus = o.positive("youngs_modulus", p.youngs_modulus);
  p.poisson_ratio = o.in_range("poisson_ratio", 0.0, 0.5, false, p.poisson_ratio);
  if (p.poisson_ratio >= 0.5) o.fail("poisson_ratio", "must be in [0, 0.5)");
  p.volume_correction = o.boolean("volume_correction", p.volume_correction);
  p.without_capillarity = o.boolean("without_capillarity", p.without_capillarity);
  if (spec.porous) {
    for (const char* key : {"porosity", "hydraulic_conductivity"})
      if (o.has(key)) o.fail(key, "is given by the case's \"porous\" section (porosity, permeability k: K = k rho g / mu)");
    if (spec.porous->capillary_constant != 0.0 && !p.without_capillarity)
      throw InputError(spec.file, "/porous/capillary_constant",
                       "method \"mpm\" has no capillary suction: must be 0 (or /methods/mpm/without_capillarity true)");
    p.porosity = spec.porous->porosity;
    p.hydraulic_conductivity = spec.porous->permeability * spec.porous->fluid_density * std::abs(spec.gravity[spec.dimension - 1]) /
                               spec.porous->fluid_viscosity;
    p.initial_saturation = spec.porous->initial_saturation;
  }
  p.porosity = o.in_range("porosity", 0.0, 1.0, true, p.porosity);
  p.hydraulic_conductivity = o.positive("hydraulic_conductivity", p.hydraulic_conductivity);
  o.finish();
  check_tank_scene(spec, "mpm", "its sides are the grid's walls", "");
  if (spec.blocks.empty()) throw InputError(spec.file, "/blocks", "method \"mpm\" needs at least one block");
  if ((has_fill(spec, BlockFill::Sand) || has_fill(spec, BlockFill::PorousBed)) && !(spec.sand.friction_angle_deg > 0.0))
    throw InputError(spec.file, "/sand/friction_angle", "method \"mpm\" needs a positive friction angle (its cone's apex sits at c cot phi)");
  return p;
}

template <int D>
mpm::Params<D> mpm_params(const CaseSpec& spec, const MpmCaseParams& own, double dx) {
  const TankSpec& tank = *spec.tank;
  mpm::Params<D> p;
  p.grid.h = own.cell_size * dx;
  for (int d = 0; d < D; ++d) {
    const double lo = tank.closed(d, -1) ? tank.min[d] : spec.domain_min[d];
    const double hi = tank.closed(d, 1) ? tank.max[d] : spec.domain_max[d];
    const long cells = std::max(1L, static_cast<long>(std::ceil((hi - lo) / p.grid.h - 1e-9)));
    p.grid.origin[d] = lo - ghost_layers * p.grid.h;
    p.grid.count[d] = cells + 1 + 2 * ghost_layers;
    p.wall_lo[d] = lo;
    p.wall_hi[d] = tank.closed(d, 1) ? hi : lo + cells * p.grid.h;
    p.rough[2 * d] = tank.rule(d, -1) == WallRule::NoSlip;
    p.rough[2 * d + 1] = tank.rule(d, 1) == WallRule::NoSlip;
  }
  p.wall_friction = spec.sand.wall_mu();
  p.gravity = to_vec<D>(spec.gravity);
  p.sand = mpm::SandModel::from(D, own.youngs_modulus, own.poisson_ratio, spec.sand.friction_angle_deg, own.volume_correction);
  p.cohesion = spec.sand.cohesion;
  p.wet_cohesion_loss = spec.sand.wet_cohesion_loss;
  p.sand_density = spec.sand.rest_density;
  p.water_density = spec.water.rest_density;
  p.eos = spec.eos;
  p.porosity = own.porosity;
  for (const BlockSpec& b : spec.blocks)
    if (b.fill == BlockFill::PorousBed)
      p.clamps.push_back({Vec<D>(to_vec<D>(b.min).array() - 1.5 * p.grid.h), Vec<D>(to_vec<D>(b.max).array() + 1.5 * p.grid.h)});
  const double g = p.gravity.norm();
  const bool grains = has_fill(spec, BlockFill::Sand) || has_fill(spec, BlockFill::PorousBed);
  if (grains && (has_fill(spec, BlockFill::Water) || own.initial_saturation > 0.0)) {
    if (g == 0.0)
      throw InputError(spec.file, "/methods/mpm/hydraulic_conductivity",
                       "the drag c_E = n^2 rho_w g / K of sand and water needs gravity");
    p.drag = mpm::drag_per_volume(own.porosity, p.water_density, g, own.hydraulic_conductivity);
  }
  p.cfl = own.cfl;
  p.relax_until = spec.relax_until;
  p.relax_rate = spec.relax_rate;
  return p;
}

template <int D>
MpmMethod<D>::MpmMethod(mpm::MpmSolver<D> solver, double dt, double support, std::vector<std::uint8_t> bed)
    : ParticleAdapter<D, mpm::Particles<D>>(solver.particles()),
      solver_(std::move(solver)),
      dt_(dt),
      support_(support),
      bed_(std::move(bed)) {}

template <int D>
void MpmMethod<D>::check_state() const {
  const mpm::Particles<D>& ps = solver_.particles();
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const char* field = !ps.x[i].allFinite() ? "x" : (!ps.v[i].allFinite() ? "v" : (!(ps.J[i] > 0.0) ? "J" : nullptr));
    if (field)
      throw BlowUpError(steps_ + 1, solver_.time(), static_cast<long>(i), ps.is_sand(i) ? "sand" : "water", field,
                        field[0] == 'J' ? "volume ratio not positive" : "not finite");
  }
}

template <int D>
double MpmMethod<D>::step() {
  this->keep_last_good();
  const double stable = solver_.stable_step();
  if (!(stable >= kShortestStepFraction * dt_)) {
    const mpm::Particles<D>& ps = solver_.particles();
    throw collapsed_step(steps_ + 1, solver_.time(), ps.v, [&](long i) { return ps.is_sand(i); }, stable, dt_);
  }
  substeps_ += solver_.advance(dt_, stable);
  check_state();
  ++steps_;
  return dt_;
}

template <int D>
ParticleView<D> MpmMethod<D>::view_of(const mpm::Particles<D>& ps) const {
  const mpm::Params<D>& params = solver_.params();
  pressure_.resize(ps.size());
  density_.resize(ps.size());
  support_field_.assign(ps.size(), support_);
  phase_ = ps.phase;
  porosity_.assign(ps.size(), 0.0);
  pore_volume_.assign(ps.size(), 0.0);
  pore_pressure_.assign(ps.size(), 0.0);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const Mat<D> tau = ps.is_sand(i) ? mpm::hencky_kirchhoff<D>(ps.Fe[i], params.sand)
                                     : mpm::water_kirchhoff<D>(ps.J[i], params.water_density, params.eos);
    pressure_[i] = -tau.trace() / (D * ps.J[i]);
    density_[i] = ps.m[i] / (ps.J[i] * ps.V0[i]);
    if (!porous_sand(ps, i)) continue;
    if (bed_[i]) phase_[i] = static_cast<std::uint8_t>(Phase::Boundary);
    porosity_[i] = params.porosity;
    pore_volume_[i] = params.porosity * ps.J[i] * ps.V0[i];
    pore_pressure_[i] = ps.pressure[i];
  }
  pressure_ = mpm::through_grid<D>(params.grid, ps, pressure_);
  ParticleView<D> view = this->motion(ps);
  view.m = ps.m;
  view.phase = phase_;
  view.pressure = pressure_;
  view.density = density_;
  view.support = support_field_;
  view.saturation = ps.saturation;
  if (!solver_.mixture() && std::find(bed_.begin(), bed_.end(), 1) == bed_.end()) return view;
  view.porosity = porosity_;
  view.pore_volume = pore_volume_;
  view.pore_water_pressure = pore_pressure_;
  return view;
}

template <int D>
std::unique_ptr<Method<D>> make_mpm_method(const CaseSpec& spec, double dx) {
  const MpmCaseParams own = read_mpm_params(spec);
  const mpm::Params<D> params = mpm_params<D>(spec, own, dx);
  check_blocks_inside<D>(spec, "mpm", "the grid's walls", params.wall_lo, params.wall_hi);
  mpm::Particles<D> ps;
  std::vector<std::uint8_t> bed;
  for (const BlockSpec& block : spec.blocks) {
    const bool porous = block.fill == BlockFill::PorousBed;
    if (block.fill == BlockFill::Water)
      seed_block<D>(block, dx, spec.water.rest_density, Phase::Water, ps);
    else
      seed_block<D>(block, dx, spec.sand.rest_density, Phase::Sand, ps);
    bed.resize(ps.size(), porous ? 1 : 0);
    if (!porous || own.initial_saturation <= 0.0) continue;
    seed_block<D>(block, dx, spec.water.rest_density, Phase::Water, ps, own.porosity, own.porosity * own.initial_saturation);
    bed.resize(ps.size(), 0);
  }
  return std::make_unique<MpmMethod<D>>(mpm::MpmSolver<D>(params, std::move(ps)), spec.dt_max, spec.support_ratio * dx,
                                        std::move(bed));
}

template mpm::Params<2> mpm_params<2>(const CaseSpec&, const MpmCaseParams&, double);
template mpm::Params<3> mpm_params<3>(const CaseSpec&, const MpmCaseParams&, double);
template class MpmMethod<2>;
template class MpmMethod<3>;
template std::unique_ptr<Method<2>> make_mpm_method<2>(const CaseSpec&, double);
template std::unique_ptr<Method<3>> make_mpm_method<3>(const CaseSpec&, double);

}  // namespace sc
