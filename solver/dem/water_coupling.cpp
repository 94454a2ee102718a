#include "dem/water_coupling.hpp"

#include <algorithm>
#include <limits>
#include <vector>

#include "dem/dem_forces.hpp"
#include "water/pressure_force.hpp"
#include "water/viscosity_force.hpp"

namespace sc::dem {

template <int D>
void bin_coupling(const Grains<D>& g, const ParticleSet<D>& water, const Params& p, CouplingGrids<D>& grids) {
  double r = 0.0;
  for (const double ri : g.radius) r = std::max(r, ri);
  const double cell = std::max(p.coupling_support, r + p.absorb_distance);
  grids.grains.build(std::span<const Vec<D>>(g.x.data(), g.x.size()), cell);
  grids.water.build(std::span<const Vec<D>>(water.x.data(), water.x.size()), cell);
}

template <int D>
Vec<D> water_grain_force(const ParticleSet<D>& water, std::size_t i, const Grains<D>& g, std::size_t k,
                         const Params& p) {
  const Vec<D> d = water.x[i] - g.x[k];
  const double r = d.norm();
  const double h = p.coupling_support;
  if (r >= h) return Vec<D>::Zero();
  const kernel::Support<D> s(h);
  const double vi = water.volume(i), vg = g.volume(k);
  return 0.25 * pressure_pair_force<D>(vi, vg, water.p[i], p.grain_pressure, d, r, s, h) +
         0.5 * viscosity_pair_force<D>(p.coupling_viscosity, vi, vg, water.v[i], g.v[k], r, s, h);
}

template <int D>
void coupling_forces(Grains<D>& g, ParticleSet<D>& water, const CouplingGrids<D>& grids, const Params& p) {
  const auto nw = static_cast<std::ptrdiff_t>(water.size());
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t s = 0; s < nw; ++s) {
    const auto i = static_cast<std::size_t>(s);
    if (water.phase_of(i) != Phase::Water) continue;
    Vec<D> f = Vec<D>::Zero();
    grids.grains.for_each_near(water.x[i], [&](std::uint32_t k) { f += water_grain_force(water, i, g, k, p); });
    water.force[i] += f;
  }
  const auto ng = static_cast<std::ptrdiff_t>(g.size());
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t s = 0; s < ng; ++s) {
    const auto k = static_cast<std::size_t>(s);
    Vec<D> f = Vec<D>::Zero();
    grids.water.for_each_near(g.x[k], [&](std::uint32_t i) {
      if (water.phase_of(i) == Phase::Water) f -= water_grain_force(water, i, g, k, p);
    });
    g.force[k] += f;
  }
}

template <int D>
std::size_t absorb_water(Grains<D>& g, ParticleSet<D>& water, const CouplingGrids<D>& grids, const Params& p) {
  constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> taker(water.size(), none);
  const auto nw = static_cast<std::ptrdiff_t>(water.size());
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t s = 0; s < nw; ++s) {
    const auto i = static_cast<std::size_t>(s);
    if (water.phase_of(i) != Phase::Water) continue;
    double best = INFINITY;
    grids.grains.for_each_near(water.x[i], [&](std::uint32_t k) {
      if (g.saturation(k, p) > p.wet_threshold) return;
      const double gap = (water.x[i] - g.x[k]).norm() - g.wet_radius(k, p);
      if (gap <= p.absorb_distance && (gap < best || (gap == best && k < taker[i]))) {
        best = gap;
        taker[i] = k;
      }
    });
  }
  // Each grain takes its water particles in index order (serial: the order is fixed).
  std::vector<double> mass(g.size()), held(g.size());
  std::vector<Vec<D>, Eigen::aligned_allocator<Vec<D>>> momentum(g.size());
  for (std::size_t k = 0; k < g.size(); ++k) {
    mass[k] = g.mass(k);
    held[k] = g.water[k];
    momentum[k] = mass[k] * g.v[k];
  }
  std::size_t absorbed = 0;
  for (std::size_t i = 0; i < water.size(); ++i) {
    if (taker[i] == none) continue;
    const std::size_t k = taker[i];
    const double take = std::min(water.m[i], g.capacity(k, p) - held[k]);
    if (!(take > 0.0)) continue;
    mass[k] += take;
    held[k] += take;
    momentum[k] += take * water.v[i];
    if (take == water.m[i]) {
      water.queue_remove(i);
      ++absorbed;
    } else {
      water.m[i] -= take;
    }
  }
  for (std::size_t k = 0; k < g.size(); ++k) {
    if (held[k] == g.water[k]) continue;
    g.water[k] = held[k];
    g.v[k] = momentum[k] / mass[k];
  }
  water.compact();
  return absorbed;
}

template <int D>
void exchange_with_water(Grains<D>& g, ParticleSet<D>& water, const Params& p, double dt, ExchangeGrids<D>& grids) {
  for (auto& f : water.force) f.setZero();
  for (auto& f : g.force) f.setZero();
  bin_coupling(g, water, p, grids.coupling);
  coupling_forces(g, water, grids.coupling, p);
  for (std::size_t i = 0; i < water.size(); ++i)
    if (water.phase_of(i) == Phase::Water) water.v[i] += (dt / water.m[i]) * water.force[i];
  for (std::size_t k = 0; k < g.size(); ++k) g.v[k] += (dt / g.mass(k)) * g.force[k];
  absorb_water(g, water, grids.coupling, p);
  bin_grains(g, p, grids.grains);
  propagate_wetness(g, grids.grains, p, dt);
}

#define SC_DEM_COUPLING(D)                                                                                     \
  template void bin_coupling<D>(const Grains<D>&, const ParticleSet<D>&, const Params&, CouplingGrids<D>&);   \
  template Vec<D> water_grain_force<D>(const ParticleSet<D>&, std::size_t, const Grains<D>&, std::size_t,     \
                                       const Params&);                                                        \
  template void coupling_forces<D>(Grains<D>&, ParticleSet<D>&, const CouplingGrids<D>&, const Params&);      \
  template std::size_t absorb_water<D>(Grains<D>&, ParticleSet<D>&, const CouplingGrids<D>&, const Params&); \
  template void exchange_with_water<D>(Grains<D>&, ParticleSet<D>&, const Params&, double, ExchangeGrids<D>&);
SC_DEM_COUPLING(2)
SC_DEM_COUPLING(3)
#undef SC_DEM_COUPLING

}  // namespace sc::dem
