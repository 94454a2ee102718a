// Density blending across splits and merges (docs/equations.md §4.7: "blend the children in").
//
// Summation density (eq 6) of a new arrangement differs from the old one by the kernel-sum error
// of the arrangement: a merged pair at h = 2 dx reads ~5 % over rest density, its fine neighbours
// ~1.3 % (spiky kernel, 2-D lattice). With a stiff equation of state (c = 15 m/s) that is ~10 kPa
// against a hydrostatic 0.6 kPa, a pressure shock at the first pass. So at each pass every
// moving particle gets an offset = (its density before the pass, carried through split and merge
// as an intensive field) − (its summation density after the pass); the density used for the
// pressure is summation + offset, and the offset decays as exp(−t/τ_blend). The new arrangement
// thus feels its discretisation error gradually, over τ_blend, instead of as a pressure shock.
#pragma once
#include <cmath>

#include "core/particle_set.hpp"
#include "neighbours/neighbour_grid.hpp"
#include "sph/density.hpp"

namespace sc {

/// After a split/merge pass: offset_i = ρ_i (carried) − Σ_j m_j W(x_ij, h_i) for moving particles.
template <int D>
void set_density_offsets(ParticleSet<D>& ps, const NeighbourGrid<D>& nb, kernel::DensityKernel k,
                         double water_rest_density) {
  const auto n = static_cast<std::int64_t>(ps.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i)
    if (ps.moves(i)) ps.density_offset[i] = ps.rho[i] - density_sum(ps, nb, i, k, water_rest_density);
}

/// ρ_i += offset_i for moving particles (after the summation of the step).
template <int D>
void add_density_offsets(ParticleSet<D>& ps) {
  const auto n = static_cast<std::int64_t>(ps.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i)
    if (ps.moves(i)) ps.rho[i] += ps.density_offset[i];
}

/// offset_i *= exp(−dt / τ_blend).
template <int D>
void decay_density_offsets(ParticleSet<D>& ps, double dt, double blend_time) {
  const double factor = std::exp(-dt / blend_time);
  for (double& offset : ps.density_offset) offset *= factor;
}

}  // namespace sc
