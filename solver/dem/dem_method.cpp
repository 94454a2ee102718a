#include "dem/dem_method.hpp"

#include <cmath>
#include <random>

#include "core/errors.hpp"
#include "scene/scene_builder.hpp"

namespace sc {

namespace {

/// Height of the material along gravity (axis D − 1): the top of the highest sand block above the
/// bottom of the lowest [m].
double material_height(const CaseSpec& spec, int dim) {
  double lo = INFINITY, hi = -INFINITY;
  for (const BlockSpec& b : spec.blocks) {
    if (b.fill != BlockFill::Sand) continue;
    lo = std::min(lo, b.min[dim - 1]);
    hi = std::max(hi, b.max[dim - 1]);
  }
  return hi - lo;
}

/// The contact plane through the side of the box [lo, hi] on axis d facing `outward` (-1: at lo,
/// +1: at hi), its normal into the box.
template <int D>
dem::Plane<D> box_side(const Vec<D>& lo, const Vec<D>& hi, int d, int outward, bool rough) {
  dem::Plane<D> w{Vec<D>::Zero(), Vec<D>::Zero(), rough};
  w.point[d] = outward < 0 ? lo[d] : hi[d];
  w.normal[d] = -outward;
  return w;
}

/// The tank's closed sides as contact planes, rough where the side is "no_slip".
template <int D>
std::vector<dem::Plane<D>> tank_planes(const TankSpec& tank) {
  std::vector<dem::Plane<D>> walls;
  for (int d = 0; d < D; ++d)
    for (const int outward : {-1, 1})
      if (tank.closed(d, outward))
        walls.push_back(box_side<D>(to_vec<D>(tank.min), to_vec<D>(tank.max), d, outward,
                                    tank.rule(d, outward) == WallRule::NoSlip));
  return walls;
}

/// One grain per lattice site of spacing dx in [lo, hi], radius 0.5 dx (1 − p u) with u uniform in
/// [0, 1), mass ρ dx^D, its centre moved off the site by at most the room its radius leaves inside
/// the site's inscribed sphere (so no two grains touch at the start and no stack stands perfectly
/// aligned).
template <int D>
void seed_grains(const Vec<D>& lo, const Vec<D>& hi, double dx, double rho, double p, unsigned seed,
                 dem::Grains<D>& g) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::array<long, D> n{};
  long count = 1;
  for (int d = 0; d < D; ++d) {
    n[d] = std::lround((hi[d] - lo[d]) / dx);
    count *= n[d];
  }
  const double mass = rho * std::pow(dx, D);
  for (long k = 0; k < count; ++k) {
    const double r = 0.5 * dx * (1.0 - p * uniform(rng));
    const double room = (0.5 * dx - r) / std::sqrt(static_cast<double>(D));
    Vec<D> x;
    long rest = k;
    for (int d = 0; d < D; ++d) {
      x[d] = lo[d] + (static_cast<double>(rest % n[d]) + 0.5) * dx + room * (2.0 * uniform(rng) - 1.0);
      rest /= n[d];
    }
    g.add(x, r, mass / dem::Grains<D>::volume_of(r));
  }
}

/// The grains' water, bridges and coupling from the case (docs/equations.md §7.5-§7.9): capacity
/// fraction c_f the porous section's porosity (0.4 without one), w_f and k_p DEM's own; with
/// bridges, Willett's law whose pull-off force 2πRγ (R = dx/2, θ = 0) is the coarse-grained bridge
/// of the case's cohesion c0 (bridge_pull_off); the coupling kernel the SPH support h, its viscosity
/// the SPH water's, the grain pressure ρ_w |g| h and the absorption reach half a spacing (a water
/// particle's site touching the grain).
template <int D>
void wet_params(const CaseSpec& spec, const DemCaseParams& own, double dx, dem::Params& p) {
  const SimulationParams sph = SimulationParams::from_case(spec, dx);
  p.water_density = sph.water.rest_density;
  if (spec.porous) p.capacity_fraction = spec.porous->porosity;
  p.wet_threshold = own.wet_threshold;
  p.propagation_rate = own.propagation_rate;
  if (own.bridges) {
    p.bridge = dem::BridgeLaw::Willett;
    const double f0 = dem::bridge_pull_off(spec.sand.cohesion, std::tan(spec.sand.friction_angle_deg * pi / 180.0),
                                           p.capacity_fraction, dx, D);
    p.surface_tension = f0 / (2.0 * pi * 0.5 * dx);
  }
  p.coupling_support = sph.support_ratio * dx;
  p.coupling_viscosity = sph.water.pair_viscosity(sph.water.viscosity);
  p.grain_pressure = p.water_density * to_vec<D>(spec.gravity).norm() * p.coupling_support;
  p.absorb_distance = 0.5 * dx;
}

/// Contact parameters of the case: the spring holds the material's full height with the asked
/// overlap; the normal dashpot gives the asked restitution for a pair of equal grains, and the
/// tangential and rolling dashpots the same damping ratio ζ for their springs (pair of equal grains:
/// m_eff = m/2, I_eff = I/2, R_eff = R/2).
template <int D>
dem::Params contact_params(const CaseSpec& spec, const DemCaseParams& own, double dx, const dem::Grains<D>& g) {
  const double m = g.mass(0), r = 0.5 * dx;
  const double layers = std::max(1.0, material_height(spec, D) / dx);
  dem::Params p;
  p.stiffness = layers * m * to_vec<D>(spec.gravity).norm() / (own.overlap * r);
  p.damping = dem::damping_for_restitution(own.restitution, p.stiffness, 0.5 * m);
  const double zeta = p.damping / (2.0 * std::sqrt(p.stiffness * 0.5 * m));
  p.tangential_damping = 2.0 * zeta * std::sqrt(p.tangential_stiffness_ratio * p.stiffness * 0.5 * m);
  const double r_eff = 0.5 * r, k_roll = 2.25 * p.stiffness * own.rolling_friction * own.rolling_friction * r_eff * r_eff;
  p.rolling_damping = 2.0 * zeta * std::sqrt(k_roll * 0.5 * g.inertia(0));
  p.friction = own.friction;
  p.wall_friction = own.wall_friction;
  p.rolling_friction = own.rolling_friction;
  wet_params<D>(spec, own, dx, p);
  return p;
}

/// Kinetic energy of the grains, translation and rotation [J].
template <int D>
double kinetic_energy(const dem::Grains<D>& g) {
  double e = 0.0;
  for (std::size_t i = 0; i < g.size(); ++i)
    e += 0.5 * (g.mass(i) * g.v[i].squaredNorm() + g.inertia(i) * g.omega[i].squaredNorm());
  return e;
}

/// The grains of one sand block, packed as a granular column is built: grains seeded on the lattice
/// over the block and a third again above it settle under gravity in a smooth mould of the block's
/// footprint (frictionless planes at its sides and bottom) until at rest; those whose centre lies
/// above the block's top less half a spacing are removed, and the rest share the block's mass ρ V
/// equally, at rest and without contact history. The column so starts as dense as a poured one, as
/// the other methods' columns do, instead of compacting by a tenth or more when released.
template <int D>
dem::Grains<D> packed_block(const CaseSpec& spec, const DemCaseParams& own, double dx, std::size_t b) {
  const BlockSpec& block = spec.blocks[b];
  Vec<D> lo = to_vec<D>(block.min), hi = to_vec<D>(block.max), top = hi;
  const double rows = std::round((hi[D - 1] - lo[D - 1]) / dx);
  top[D - 1] = lo[D - 1] + (rows + std::ceil(rows / 3.0) + 1.0) * dx;
  dem::Grains<D> g;
  seed_grains<D>(lo, top, dx, spec.sand.rest_density, own.polydispersity, static_cast<unsigned>(b + 1), g);
  if (g.size() == 0) return g;  // a block narrower than a spacing holds no grain
  dem::Params p = contact_params<D>(spec, own, dx, g);
  std::vector<dem::Plane<D>> mould;
  for (int d = 0; d < D; ++d)
    for (const int outward : {-1, 1})
      if (d < D - 1 || outward < 0) mould.push_back(box_side<D>(lo, hi, d, outward, false));  // open top
  const Vec<D> gravity = to_vec<D>(spec.gravity);
  const double h = dem::stable_step(g, p), weight_scale = g.size() * g.mass(0) * gravity.norm() * (top - lo)[D - 1];
  dem::Contacts<D> contacts;
  for (int chunk = 0; chunk < 200; ++chunk) {  // at most 200 x 200 contact steps
    for (int s = 0; s < 200; ++s) dem::step(g, contacts, p, gravity, std::span<const dem::Plane<D>>(mould), h);
    if (kinetic_energy(g) < 1e-10 * weight_scale) break;
  }
  dem::Grains<D> kept;
  for (std::size_t i = 0; i < g.size(); ++i)
    if (g.x[i][D - 1] <= hi[D - 1] - 0.5 * dx) kept.add(g.x[i], g.radius[i], 1.0);
  double volume = 1.0;
  for (int d = 0; d < D; ++d) volume *= hi[d] - lo[d];
  const double mass = spec.sand.rest_density * volume / static_cast<double>(kept.size());
  for (std::size_t i = 0; i < kept.size(); ++i) kept.dry_mass[i] = mass;
  return kept;
}

/// Appends the grains of `from` to `to`, in order.
template <int D>
void append(const dem::Grains<D>& from, dem::Grains<D>& to) {
  for (std::size_t i = 0; i < from.size(); ++i) {
    const std::size_t k = to.add(from.x[i], from.radius[i], 1.0);
    to.dry_mass[k] = from.dry_mass[i];
  }
}

/// The case without its sand blocks and porous section: the SPH scene of its water. Its particles
/// collide with the tank's sides (Müller 2003's collision, boundary/wall_collision.hpp): its density
/// does not count the grains, so grains settling on it can press it through the wall particles.
CaseSpec water_only(const CaseSpec& spec) {
  CaseSpec water = spec;
  std::erase_if(water.blocks, [](const BlockSpec& b) { return b.fill != BlockFill::Water; });
  water.porous.reset();
  water.has_sand = false;
  water.tank->collision = true;
  return water;
}

}  // namespace

DemCaseParams read_dem_params(const CaseSpec& spec) {
  const json own = own_parameters(spec, "dem", "DEM");
  JsonObject o(own, "/methods/dem", spec.file);
  DemCaseParams p;
  p.friction = o.non_negative("friction", p.friction);
  p.rolling_friction = o.non_negative("rolling_friction", p.rolling_friction);
  p.wall_friction = o.non_negative("wall_friction", p.friction);
  p.restitution = o.in_range("restitution", 0.0, 1.0, false, p.restitution);
  if (p.restitution <= 0.0) o.fail("restitution", "must be in (0, 1]");
  p.overlap = o.in_range("overlap", 0.0, 0.1, true, p.overlap);
  p.polydispersity = o.in_range("polydispersity", 0.0, 0.5, false, p.polydispersity);
  p.packed = o.boolean("packed", p.packed);
  p.wet_threshold = o.in_range("wet_threshold", 0.0, 1.0, false, p.wet_threshold);
  if (p.wet_threshold <= 0.0) o.fail("wet_threshold", "must be in (0, 1]");
  p.moisture = o.in_range("moisture", 0.0, p.wet_threshold, false, p.moisture);
  p.propagation_rate = o.non_negative("propagation_rate", p.propagation_rate);
  if (p.propagation_rate * spec.dt_max > 1.0)
    o.fail("propagation_rate", "times the case's step (time.dt) must be at most 1 (a grain gives at most its excess)");
  p.bridges = o.boolean("bridges", p.bridges);
  if (p.bridges && !(spec.sand.cohesion > 0.0))
    o.fail("bridges", "needs the case's sand cohesion > 0 (the bridges' pull-off force comes from it)");
  o.finish();
  check_tank_scene(spec, "dem", "its closed sides are the contact walls", "");
  double g2 = 0.0;
  for (const double g : spec.gravity) g2 += g * g;
  if (g2 == 0.0) throw InputError(spec.file, "/gravity", "method \"dem\" needs gravity (the weight of the material sets the contact stiffness)");
  if (spec.blocks.empty()) throw InputError(spec.file, "/blocks", "method \"dem\" needs at least one sand block");
  for (std::size_t b = 0; b < spec.blocks.size(); ++b)
    if (spec.blocks[b].fill != BlockFill::Sand && spec.blocks[b].fill != BlockFill::Water)
      throw InputError(spec.file, "/blocks/" + std::to_string(b) + "/phase",
                       "method \"dem\" runs sand and water blocks only");
  return p;
}

template <int D>
DemMethod<D>::DemMethod(dem::Grains<D> grains, const dem::Params& params, std::vector<dem::Plane<D>> walls,
                        const Vec<D>& gravity, double dt, double contact_step, std::optional<Simulator<D>> water)
    : ParticleAdapter<D, DemFrame<D>>(DemFrame<D>{}),
      grains_(std::move(grains)),
      params_(params),
      walls_(std::move(walls)),
      gravity_(gravity),
      dt_(dt),
      contact_step_(contact_step),
      water_(std::move(water)) {
  wet_ = water_.has_value();
  for (const double w : grains_.water) wet_ = wet_ || w > 0.0;
  refresh_frame();
  this->keep_last_good();
}

template <int D>
void DemMethod<D>::step_grains(double dt) {
  const int substeps = std::max(1, static_cast<int>(std::ceil(dt / contact_step_ - 1e-9)));
  const double h = dt / substeps;
  for (int s = 0; s < substeps; ++s) {
    {
      auto scope = timers_.time(dem::DemStage::Contacts);
      dem::update_neighbours(grains_, params_, std::span<const dem::Plane<D>>(walls_), contacts_);
      dem::grain_forces(grains_, contacts_, params_, gravity_, std::span<const dem::Plane<D>>(walls_), h);
    }
    auto scope = timers_.time(dem::DemStage::Integration);
    dem::integrate(grains_, params_, h);
  }
  contact_steps_ += substeps;
}

template <int D>
double DemMethod<D>::step() {
  this->keep_last_good();
  double dt = dt_;
  if (water_) {
    auto scope = timers_.time(dem::DemStage::Water);
    dt = water_->step();
  }
  step_grains(dt);
  for (std::size_t i = 0; i < grains_.size(); ++i)
    if (!grains_.x[i].allFinite() || !grains_.v[i].allFinite())
      throw BlowUpError(steps_ + 1, time_, static_cast<long>(i), "sand", grains_.x[i].allFinite() ? "v" : "x", "not finite");
  if (water_) {
    auto scope = timers_.time(dem::DemStage::Water);
    dem::exchange_with_water(grains_, water_->particles(), params_, dt, exchange_);
  }
  time_ += dt;
  ++steps_;
  refresh_frame();
  return dt;
}

template <int D>
void DemMethod<D>::refresh_frame() {
  DemFrame<D>& f = frame_;
  const dem::Grains<D>& g = grains_;
  f = DemFrame<D>{};
  f.wet = wet_;
  for (std::size_t i = 0; i < g.size(); ++i) {
    f.x.push_back(g.x[i]);
    f.v.push_back(g.v[i]);
    f.m.push_back(g.mass(i));
    f.density.push_back(g.mass(i) / g.volume(i));
    f.support.push_back(g.radius[i]);
    f.phase.push_back(static_cast<std::uint8_t>(Phase::Sand));
    if (!wet_) continue;
    f.porosity.push_back(params_.capacity_fraction);
    f.pore_volume.push_back(g.capacity(i, params_) / params_.water_density);
    f.held.push_back(g.water[i]);
    f.saturation.push_back(g.saturation(i, params_));
  }
  if (!water_) return;
  const ParticleSet<D>& w = water_->particles();
  for (std::size_t i = 0; i < w.size(); ++i) {
    f.x.push_back(w.x[i]);
    f.v.push_back(w.v[i]);
    f.m.push_back(w.m[i]);
    f.density.push_back(w.rho[i]);
    f.support.push_back(w.h[i]);
    f.phase.push_back(w.phase[i]);
    for (auto* field : {&f.porosity, &f.pore_volume, &f.held, &f.saturation}) field->push_back(0.0);
  }
}

template <int D>
ParticleView<D> DemMethod<D>::view_of(const DemFrame<D>& f) const {
  ParticleView<D> view = this->motion(f);
  view.m = f.m;
  view.phase = f.phase;
  view.density = f.density;
  view.support = f.support;
  if (!f.wet) return view;
  view.porosity = f.porosity;
  view.pore_volume = f.pore_volume;
  view.held_water = f.held;
  view.saturation = f.saturation;
  return view;
}

template <int D>
std::unique_ptr<Method<D>> make_dem_method(const CaseSpec& spec, double dx) {
  const DemCaseParams own = read_dem_params(spec);
  dem::Grains<D> g;
  for (std::size_t b = 0; b < spec.blocks.size(); ++b) {
    const BlockSpec& block = spec.blocks[b];
    if (block.fill != BlockFill::Sand) continue;
    if (own.packed) append<D>(packed_block<D>(spec, own, dx, b), g);
    else seed_grains<D>(to_vec<D>(block.min), to_vec<D>(block.max), dx, spec.sand.rest_density, own.polydispersity,
                        static_cast<unsigned>(b + 1), g);
  }
  if (g.size() == 0)
    throw InputError(spec.file, "/blocks", "method \"dem\": no grain fits in the sand blocks at spacing " +
                                               json(dx).dump() + " m");
  const dem::Params p = contact_params<D>(spec, own, dx, g);
  for (std::size_t i = 0; i < g.size(); ++i) g.water[i] = own.moisture * g.capacity(i, p);
  const double h_max = dem::stable_step(g, p);
  const CaseSpec water = water_only(spec);
  std::optional<Simulator<D>> sph;
  if (!water.blocks.empty()) sph.emplace(build_scene<D>(water, dx), SimulationParams::from_case(water, dx));
  return std::make_unique<DemMethod<D>>(std::move(g), p, tank_planes<D>(*spec.tank), to_vec<D>(spec.gravity),
                                        spec.dt_max, h_max, std::move(sph));
}

template class DemMethod<2>;
template class DemMethod<3>;
template std::unique_ptr<Method<2>> make_dem_method<2>(const CaseSpec&, double);
template std::unique_ptr<Method<3>> make_dem_method<3>(const CaseSpec&, double);

}  // namespace sc
