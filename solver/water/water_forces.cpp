#include "water/water_forces.hpp"

#include "water/pressure_force.hpp"
#include "water/surface_tension.hpp"
#include "water/viscosity_force.hpp"

namespace sc {

namespace {

/// The reaction of the water's surface tension on a (moving) sand particle i: the pair forces of its water
/// neighbours, each the exact negative of the force add_water_forces gives that neighbour, so
/// water and sand together keep their momentum.
template <int D>
Vec<D> surface_tension_from_water(const ParticleSet<D>& ps, const NeighbourGrid<D>& nb, std::size_t i,
                                  double kappa_prime) {
  const kernel::Support<D> si(ps.h[i]);
  Vec<D> f = Vec<D>::Zero();
  for (const auto j : nb.of(i)) {
    if (ps.phase_of(j) != Phase::Water) continue;
    const Vec<D> d = ps.x[i] - ps.x[j];
    f += surface_tension_pair_force<D>(kappa_prime, ps.m[i], ps.m[j], d, d.norm(), si, ps.h[j]);
  }
  return f;
}

}  // namespace

template <int D>
void add_water_forces(ParticleSet<D>& ps, const NeighbourGrid<D>& nb, const WaterParams& params,
                      const MatArray<D>& correction) {
  const bool corrected = params.gradient_correction && correction.size() == ps.size();
  const auto n = static_cast<std::int64_t>(ps.size());
  const double kappa_prime = params.surface_tension / params.reference_mass;
  // Dynamic: the work per particle varies (walls, free surface) and moving particles are stored first.
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t i = 0; i < n; ++i) {
    if (ps.phase_of(i) == Phase::Sand && kappa_prime != 0.0)
      ps.force[i] += surface_tension_from_water(ps, nb, i, kappa_prime);
    if (ps.phase_of(i) != Phase::Water) continue;
    const double Vi = ps.volume(i), Pi = ps.p[i], mi = ps.m[i];
    const Vec<D> xi = ps.x[i], vi = ps.v[i];
    const kernel::Support<D> si(ps.h[i]);
    Vec<D> f = Vec<D>::Zero();
    for (const auto j : nb.of(i)) {
      if (j == static_cast<std::size_t>(i)) continue;
      const Vec<D> d = xi - ps.x[j];
      const double r = d.norm();
      const double Vj = ps.volume(j);
      const Vec<D> fp = pressure_pair_force<D>(Vi, Vj, Pi, ps.p[j], d, r, si, ps.h[j], params.mueller_half_pressure);
      f += corrected ? corrected_pair_term<D>(correction[i], correction[j], fp) : fp;
      const bool boundary = ps.phase_of(j) == Phase::Boundary;
      if (!boundary || ps.rough[j])
        f += viscosity_pair_force<D>(params.viscosity, Vi, Vj, vi, ps.v[j], r, si, ps.h[j]);
      if (!boundary && kappa_prime != 0.0)
        f += surface_tension_pair_force<D>(kappa_prime, mi, ps.m[j], d, r, si, ps.h[j]);
    }
    ps.force[i] += f;
  }
}

template void add_water_forces<2>(ParticleSet<2>&, const NeighbourGrid<2>&, const WaterParams&, const MatArray<2>&);
template void add_water_forces<3>(ParticleSet<3>&, const NeighbourGrid<3>&, const WaterParams&, const MatArray<3>&);

}  // namespace sc
