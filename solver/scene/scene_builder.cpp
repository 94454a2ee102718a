#include "scene/scene_builder.hpp"

#include <cmath>
#include <cstdio>

#include "porous/porous_setup.hpp"
#include "sand/rigid_body.hpp"
#include "scene/mesh_fill.hpp"
#include "sph/kernels.hpp"
#include "sph/lattice_sum.hpp"

namespace sc {

template <int D>
double lattice_mass(double rho0, double dx, double h, kernel::DensityKernel kind) {
  return rho0 / lattice_density_sum<D>(dx, h, kind);
}

template <int D>
std::vector<Vec<D>, Eigen::aligned_allocator<Vec<D>>> lattice_points(const Vec<D>& min, const Vec<D>& max, double dx) {
  std::array<long, D> count;
  for (int d = 0; d < D; ++d) count[d] = std::max(1L, std::lround((max[d] - min[d]) / dx));
  std::vector<Vec<D>, Eigen::aligned_allocator<Vec<D>>> out;
  std::array<long, D> k;
  k.fill(0);
  while (true) {
    Vec<D> p;
    for (int d = 0; d < D; ++d) p[d] = min[d] + (k[d] + 0.5) * dx;
    out.push_back(p);
    int d = 0;
    while (d < D && ++k[d] >= count[d]) k[d++] = 0;
    if (d == D) break;
  }
  return out;
}

namespace {

template <int D>
void add_particle(ParticleSet<D>& ps, const Vec<D>& x, Phase phase, double mass, double h, double rho0, bool rough) {
  const std::size_t i = ps.append();
  ps.x[i] = x;
  ps.m[i] = mass;
  ps.h[i] = h;
  ps.rho0[i] = rho0;
  ps.rho[i] = rho0;
  ps.phase[i] = static_cast<std::uint8_t>(phase);
  ps.rough[i] = rough ? 1 : 0;
}

/// Wall layers of the tank: lattice points outside [min, max] within `layers` spacings of a side
/// that is not open. A point is rough if any wall side it lies beyond is no-slip.
template <int D>
void add_tank(ParticleSet<D>& ps, const TankSpec& tank, double dx, int layers, double h, double mass, double rho0) {
  Vec<D> lo = to_vec<D>(tank.min), hi = to_vec<D>(tank.max);
  Vec<D> ext_lo = lo, ext_hi = hi;
  for (int d = 0; d < D; ++d) {
    if (tank.closed(d, -1)) ext_lo[d] -= layers * dx;
    if (tank.closed(d, 1)) ext_hi[d] += layers * dx;
  }
  for (const Vec<D>& p : lattice_points<D>(ext_lo, ext_hi, dx)) {
    bool outside = false, rough = false;
    for (int d = 0; d < D; ++d) {
      const int outward = p[d] < lo[d] ? -1 : (p[d] > hi[d] ? 1 : 0);
      if (outward == 0) continue;
      outside = true;
      if (tank.rule(d, outward) == WallRule::NoSlip) rough = true;
    }
    if (outside) add_particle(ps, p, Phase::Boundary, mass, h, rho0, rough);
  }
}

/// Gives the particles [first, end) of a block the rigid spin ω about their centre of mass (all
/// of a block's particles have the same mass): v = ω × (x − x_cm).
template <int D>
void spin_block(ParticleSet<D>& ps, std::size_t first, const std::vector<double>& angular_velocity) {
  if (angular_velocity.empty()) return;
  const AngVec<D> omega = Eigen::Map<const AngVec<D>>(angular_velocity.data());
  Vec<D> centre = Vec<D>::Zero();
  for (std::size_t i = first; i < ps.size(); ++i) centre += ps.x[i];
  centre /= static_cast<double>(ps.size() - first);
  for (std::size_t i = first; i < ps.size(); ++i) ps.v[i] = spin_velocity<D>(omega, ps.x[i] - centre);
}

}  // namespace

template <int D>
ParticleSet<D> build_scene(const CaseSpec& spec, double dx) {
  ParticleSet<D> ps;
  const Resolution res = resolve(spec, dx);
  const double h = res.h, mass = res.water_mass, sand_mass = res.sand_mass;
  const double rho0 = spec.water.rest_density, sand_rho0 = spec.sand.rest_density;
  for (const BlockSpec& block : spec.blocks) {
    const bool sand = block.fill == BlockFill::Sand;
    const std::size_t first = ps.size();
    for (const Vec<D>& p : lattice_points<D>(to_vec<D>(block.min), to_vec<D>(block.max), dx))
      add_particle(ps, p, block.phase(), sand ? sand_mass : mass, h, sand ? sand_rho0 : rho0, false);
    spin_block<D>(ps, first, block.angular_velocity);
  }
  if constexpr (D == 3)
    for (const MeshSpec& m : spec.meshes) {
      const bool sand = m.phase == Phase::Sand;
      for (const Vec<3>& p : mesh_particles(spec, m, dx))
        add_particle(ps, p, m.phase, sand ? sand_mass : mass, h, sand ? sand_rho0 : rho0, false);
    }
  if (spec.porous) init_porous(ps, *spec.porous);
  if (spec.tank) add_tank(ps, *spec.tank, dx, res.wall_layers, h, mass, rho0);
  return ps;
}

namespace {

/// Points of the lattice of spacing dx in the box [lo, hi) (as lattice_points makes them).
double lattice_count(const std::vector<double>& lo, const std::vector<double>& hi, double dx) {
  double n = 1.0;
  for (std::size_t d = 0; d < lo.size(); ++d) n *= std::max(1.0, std::round((hi[d] - lo[d]) / dx));
  return n;
}

/// Wall particles of the tank: the lattice of the box grown by the wall layers on its closed sides,
/// less the lattice of the box itself (as add_tank makes them).
double tank_wall_count(const TankSpec& tank, double dx, double h) {
  const double grow = tank_wall_layers(h, dx) * dx;
  std::vector<double> lo = tank.min, hi = tank.max;
  for (std::size_t d = 0; d < lo.size(); ++d) {
    if (tank.closed(static_cast<int>(d), -1)) lo[d] -= grow;
    if (tank.closed(static_cast<int>(d), 1)) hi[d] += grow;
  }
  return lattice_count(lo, hi, dx) - lattice_count(tank.min, tank.max, dx);
}

}  // namespace

Resolution resolve(const CaseSpec& spec, double dx) {
  Resolution r;
  r.dx = dx;
  r.h = spec.support_ratio * dx;
  const auto mass = [&](double rho0) {
    return spec.dimension == 2 ? lattice_mass<2>(rho0, dx, r.h, spec.water.density_kernel)
                               : lattice_mass<3>(rho0, dx, r.h, spec.water.density_kernel);
  };
  r.water_mass = mass(spec.water.rest_density);
  r.sand_mass = spec.has_sand ? mass(spec.sand.rest_density) : 0.0;
  r.wall_layers = tank_wall_layers(r.h, dx);
  return r;
}

double estimate_particles(const CaseSpec& spec, double dx) {
  double n = 0.0;
  for (const BlockSpec& b : spec.blocks) n += lattice_count(b.min, b.max, dx);
  const std::vector<double>& box_min = spec.tank ? spec.tank->min : spec.domain_min;
  const std::vector<double>& box_max = spec.tank ? spec.tank->max : spec.domain_max;
  n += static_cast<double>(spec.meshes.size()) * lattice_count(box_min, box_max, dx);
  if (spec.tank) n += tank_wall_count(*spec.tank, dx, spec.support_ratio * dx);
  return n;
}

void check_particle_count(const CaseSpec& spec, double dx, double limit, const std::string& json_path) {
  const double n = estimate_particles(spec, dx);
  if (n <= limit) return;
  char text[256];
  std::snprintf(text, sizeof text,
                "case '%s' at spacing %g m would make about %.3g particles, above the limit of %.3g "
                "(a mistyped spacing? a larger run needs --max-particles)",
                spec.name.c_str(), dx, n, limit);
  throw InputError(spec.file, json_path, text);
}

template double lattice_mass<2>(double, double, double, kernel::DensityKernel);
template double lattice_mass<3>(double, double, double, kernel::DensityKernel);
template std::vector<Vec<2>, Eigen::aligned_allocator<Vec<2>>> lattice_points<2>(const Vec<2>&, const Vec<2>&, double);
template std::vector<Vec<3>, Eigen::aligned_allocator<Vec<3>>> lattice_points<3>(const Vec<3>&, const Vec<3>&, double);
template ParticleSet<2> build_scene<2>(const CaseSpec&, double);
template ParticleSet<3> build_scene<3>(const CaseSpec&, double);

}  // namespace sc
