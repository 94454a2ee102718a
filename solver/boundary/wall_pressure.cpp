#include "boundary/wall_pressure.hpp"

#include <algorithm>

#include "sph/kernels.hpp"

namespace sc {

template <int D>
void extrapolate_wall_pressure(ParticleSet<D>& ps, const NeighbourGrid<D>& nb, const Vec<D>& gravity,
                               const EquationOfState& eos) {
  const auto n = static_cast<std::int64_t>(ps.size());
  // Dynamic: the work per particle varies (walls, free surface) and moving particles are stored first.
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t w = 0; w < n; ++w) {
    if (ps.phase_of(w) != Phase::Boundary) continue;
    double sum_w = 0.0, sum_p = 0.0, sum_g = 0.0;
    for (const auto f : nb.of(w)) {
      if (!ps.moves(f)) continue;
      const Vec<D> d = ps.x[w] - ps.x[f];
      const double W = kernel::poly6<D>(d.norm(), ps.h[w]);
      sum_w += W;
      sum_p += ps.p[f] * W;
      sum_g += ps.rho[f] * gravity.dot(d) * W;
    }
    double p = sum_w > 0.0 ? (sum_p + sum_g) / sum_w : 0.0;
    if (eos.clamp_negative) p = std::max(0.0, p);
    ps.p[w] = p;
    ps.rho[w] = eos.density(p, ps.rho0[w]);
  }
}

template void extrapolate_wall_pressure<2>(ParticleSet<2>&, const NeighbourGrid<2>&, const Vec<2>&, const EquationOfState&);
template void extrapolate_wall_pressure<3>(ParticleSet<3>&, const NeighbourGrid<3>&, const Vec<3>&, const EquationOfState&);

}  // namespace sc
