#include "sand/sand_forces.hpp"

#include "sand/contact.hpp"
#include "sand/frictional_force.hpp"
#include "sand/frictional_stress.hpp"
#include "sand/strain_rate.hpp"
#include "sand/yield.hpp"
#include "porous/effective_stress.hpp"
#include "porous/partial_water_pressure.hpp"
#include "porous/wet_cohesion.hpp"
#include "water/pressure_force.hpp"
#include "water/viscosity_force.hpp"

namespace sc {

namespace {

bool is_sand(std::uint8_t phase) { return static_cast<Phase>(phase) == Phase::Sand; }

/// Length of the rigid stress (eq 12a) of particle i.
template <int D>
double rigid_length(const ParticleSet<D>& ps, std::size_t i, const SandParams& sand) {
  return rigid_stress_length(sand.rigid_length, ps.h[i], rest_spacing<D>(ps.m[i], ps.rho[i]));
}

/// Contact force on i from j (contact_force). The law (a wall particle counts as infinitely heavy)
/// is built only for a pair that overlaps: any other pair gets zero from contact_force anyway.
/// `spacing_i`, `spacing_j`: the rest spacings of i and j.
template <int D>
Vec<D> pair_contact_force(const ParticleSet<D>& ps, std::size_t i, double spacing_i, std::size_t j, double spacing_j,
                          const Vec<D>& d, double r, const SandParams& sand, double sound_speed, double dt) {
  const double s = 0.5 * (spacing_i + spacing_j);
  if (!(r < s)) return Vec<D>::Zero();
  const double mj = ps.moves(j) ? ps.m[j] : 0.0;
  const ContactLaw law = contact_law(ps.m[i], mj, s, sound_speed, sand.contact_damping,
                                     std::tan(sand.friction_angle_deg * pi / 180.0), dt);
  return contact_force<D>(law, d, r, ps.v[i], ps.v[j], s);
}

}  // namespace

template <int D>
void update_sand_state(ParticleSet<D>& ps, const NeighbourGrid<D>& nb, const SandParams& sand, double gravity,
                       double dt, MatArray<D>& stress, VecArrayOf<D>& predicted, double stress_scale,
                       double pore_stiffness) {
  stress.resize(ps.size());
  predicted.resize(ps.size());
  const double sin_phi = sand.sin_phi();
  const double strength = yield_strength_factor(sand.yield_surface);
  const auto n = static_cast<std::int64_t>(ps.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) predicted[i] = ps.moves(i) ? Vec<D>(ps.v[i] + (dt / ps.m[i]) * ps.force[i]) : ps.v[i];
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t i = 0; i < n; ++i) {
    ps.rigid[i] = 0;
    ps.strain_rate[i] = 0.0;
    stress[i].setZero();
    if (!is_sand(ps.phase[i])) continue;
    const Mat<D> Dr = strain_rate<D>(velocity_gradient(ps, nb, i, &predicted));
    const double p = effective_pressure(granular_pressure(ps.p[i], ps.rho0[i], gravity, rest_spacing<D>(ps.m[i], ps.rho0[i])),
                                        stress_scale, pore_stiffness, ps.saturation_of(i));  // eq 32
    const double L = rigid_length(ps, i, sand);
    ps.strain_rate[i] = Dr.norm();
    const double c = sand.wet_cohesion_loss ? wet_cohesion(sand.cohesion, ps.saturation_of(i)) : sand.cohesion;
    ps.rigid[i] = is_rigid<D>(rigid_stress<D>(Dr, ps.rho[i], L, dt), p, sin_phi, c, strength) ? 1 : 0;
    if (!ps.rigid[i] || !sand.rigid_clusters) stress[i] = -frictional_stress<D>(Dr, p, sin_phi);
  }
}

template <int D>
void add_sand_forces(ParticleSet<D>& ps, const NeighbourGrid<D>& nb, const SandParams& sand, const WaterParams& water,
                     double sound_speed, double dt, const MatArray<D>& correction, VecArrayOf<D>& wall_force) {
  wall_force.resize(ps.size());
  const bool corrected = water.gradient_correction && correction.size() == ps.size();
  const auto n = static_cast<std::int64_t>(ps.size());
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t i = 0; i < n; ++i) {
    wall_force[i].setZero();
    if (!is_sand(ps.phase[i])) continue;
    const double Vi = ps.volume(i), Pi = ps.p[i], spacing_i = rest_spacing<D>(ps.m[i], ps.rho0[i]);
    const Vec<D> xi = ps.x[i], vi = ps.v[i];
    const kernel::Support<D> si(ps.h[i]);
    NeighbourSpacing<D> spacing_of;
    Vec<D> f = Vec<D>::Zero(), wall = Vec<D>::Zero();
    for (const auto j : nb.of(i)) {
      if (j == static_cast<std::size_t>(i)) continue;
      const Vec<D> d = xi - ps.x[j];
      const double r = d.norm();
      const double Vj = ps.volume(j);
      const Vec<D> fp0 = pressure_pair_force<D>(Vi, Vj, Pi, ps.p[j], d, r, si, ps.h[j], water.mueller_half_pressure);
      const Vec<D> fp = corrected ? corrected_pair_term<D>(correction[i], correction[j], fp0) : fp0;
      f += fp;
      if (is_sand(ps.phase[j])) {
        if (sand.viscosity > 0.0)
          f += viscosity_pair_force<D>(water.pair_viscosity(sand.viscosity), Vi, Vj, vi, ps.v[j], r, si, ps.h[j]);
        continue;
      }
      const Vec<D> fc = pair_contact_force(ps, i, spacing_i, j, spacing_of(ps.m[j], ps.rho0[j]), d, r, sand, sound_speed, dt);
      f += fc;
      if (ps.moves(j)) f += viscosity_pair_force<D>(water.pair_viscosity(water.viscosity), Vi, Vj, vi, ps.v[j], r, si, ps.h[j]);
      else if (ps.rough[j]) wall += fp + fc;
    }
    ps.force[i] += f;
    wall_force[i] = wall;
  }
}

template <int D>
void add_frictional_forces(ParticleSet<D>& ps, const NeighbourGrid<D>& nb, const MatArray<D>& stress,
                           const MatArray<D>& correction) {
  const bool corrected = correction.size() == ps.size();
  const auto n = static_cast<std::int64_t>(ps.size());
  // A pair of unstressed particles (rigid ones) adds ±0 to f, which starts at +0, so skipping it
  // leaves f bitwise unchanged.
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t i = 0; i < n; ++i) {
    if (!is_sand(ps.phase[i])) continue;
    const bool unstressed = stress[i].isZero(0.0);
    const double Vi = ps.volume(i);
    const Vec<D> xi = ps.x[i];
    const kernel::Support<D> si(ps.h[i]);
    Vec<D> f = Vec<D>::Zero();
    for (const auto j : nb.of(i)) {
      if (j == static_cast<std::size_t>(i) || !is_sand(ps.phase[j]) || (unstressed && stress[j].isZero(0.0))) continue;
      const Vec<D> d = xi - ps.x[j];
      const Vec<D> fp = frictional_pair_force<D>(Vi, ps.volume(j), stress[i], stress[j], d, d.norm(), si,
                                                 kernel::support_of<D>(ps.h[j], si));
      f += corrected ? corrected_pair_term<D>(correction[i], correction[j], fp) : fp;
    }
    ps.force[i] += f;
  }
}

template <int D>
void add_water_sand_contact(ParticleSet<D>& ps, const NeighbourGrid<D>& nb, const SandParams& sand, double sound_speed,
                            double dt) {
  const auto n = static_cast<std::int64_t>(ps.size());
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t i = 0; i < n; ++i) {
    if (ps.phase_of(i) != Phase::Water) continue;
    const double spacing_i = rest_spacing<D>(ps.m[i], ps.rho0[i]);
    NeighbourSpacing<D> spacing_of;
    Vec<D> f = Vec<D>::Zero();
    for (const auto j : nb.of(i)) {
      if (!is_sand(ps.phase[j])) continue;
      const Vec<D> d = ps.x[i] - ps.x[j];
      f += pair_contact_force(ps, i, spacing_i, j, spacing_of(ps.m[j], ps.rho0[j]), d, d.norm(), sand, sound_speed, dt);
    }
    ps.force[i] += f;
  }
}

template <int D>
void add_partial_water_wall_contact(ParticleSet<D>& ps, const NeighbourGrid<D>& nb, const SandParams& sand,
                                    double sound_speed, double dt, double full_water_mass) {
  const auto n = static_cast<std::int64_t>(ps.size());
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t i = 0; i < n; ++i) {
    if (!is_partial_water(ps, i, full_water_mass)) continue;
    const double spacing_i = rest_spacing<D>(ps.m[i], ps.rho0[i]);
    NeighbourSpacing<D> spacing_of;
    Vec<D> f = Vec<D>::Zero();
    for (const auto j : nb.of(i)) {
      if (ps.phase_of(j) != Phase::Boundary || ps.porosity_of(j) != 0.0) continue;
      const Vec<D> d = ps.x[i] - ps.x[j];
      f += pair_contact_force(ps, i, spacing_i, j, spacing_of(ps.m[j], ps.rho0[j]), d, d.norm(), sand, sound_speed, dt);
    }
    ps.force[i] += f;
  }
}

template <int D>
void add_wall_friction(ParticleSet<D>& ps, const VecArrayOf<D>& wall_force, double mu, double dt) {
  const auto n = static_cast<std::int64_t>(ps.size());
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t i = 0; i < n; ++i)
    if (is_sand(ps.phase[i])) ps.force[i] += wall_friction_force<D>(wall_force[i], ps.v[i], ps.force[i], ps.m[i], mu, dt);
}

#define SC_INSTANTIATE(D)                                                                                         \
  template void update_sand_state<D>(ParticleSet<D>&, const NeighbourGrid<D>&, const SandParams&, double, double, \
                                     MatArray<D>&, VecArrayOf<D>&, double, double);                                            \
  template void add_sand_forces<D>(ParticleSet<D>&, const NeighbourGrid<D>&, const SandParams&, const WaterParams&, \
                                   double, double, const MatArray<D>&, VecArrayOf<D>&);                                   \
  template void add_frictional_forces<D>(ParticleSet<D>&, const NeighbourGrid<D>&, const MatArray<D>&,             \
                                         const MatArray<D>&);                                                     \
  template void add_water_sand_contact<D>(ParticleSet<D>&, const NeighbourGrid<D>&, const SandParams&, double,   \
                                          double);                                                                \
  template void add_partial_water_wall_contact<D>(ParticleSet<D>&, const NeighbourGrid<D>&, const SandParams&,     \
                                                  double, double, double);                                        \
  template void add_wall_friction<D>(ParticleSet<D>&, const VecArrayOf<D>&, double, double);
SC_INSTANTIATE(2)
SC_INSTANTIATE(3)
#undef SC_INSTANTIATE

}  // namespace sc
