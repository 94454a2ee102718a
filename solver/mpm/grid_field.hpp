// A particle field seen through the grid: the mass-weighted nodal average of each phase's values,
// interpolated back to that phase's particles with the same quadratic B-spline weights. This is
// the field MPM's momentum balance resolves (one value per node), without the cell-to-cell
// staircase of the particles' own stresses; the view reports the water pressure this way, as
// FLIP reports its cell-centre pressure interpolated to the particles (docs/equations.md §9).
#pragma once
#include <vector>

#include "mpm/bspline.hpp"
#include "mpm/grid.hpp"
#include "mpm/particles.hpp"

namespace sc::mpm {

/// The 1-D weights of a particle at x along each axis (bspline.hpp AxisWeights).
/// [Jiang 2016: quadratic B-spline]
template <int D>
AxisWeights<D> axis_weights(const Grid<D>& grid, const Vec<D>& x) {
  const std::array<long, D> b = grid.base(x);
  AxisWeights<D> w{};
  for (int d = 0; d < D; ++d)
    for (int k = 0; k < 3; ++k) w[d][k] = bspline(-(grid.origin[d] + static_cast<double>(b[d] + k) * grid.h - x[d]) / grid.h);
  return w;
}

/// Calls visit(k, r, w) for the 3^D nodes of particle x's stencil (node index, x_i − x, weight), in a
/// fixed order, with the particle's 1-D weights `axes`.
template <int D, class Visit>
void for_stencil(const Grid<D>& grid, const Vec<D>& x, const AxisWeights<D>& axes, Visit&& visit) {
  constexpr int stencil = D == 2 ? 9 : 27;
  const std::array<long, D> b = grid.base(x);
  for (int t = 0; t < stencil; ++t) {
    std::array<long, D> node{};
    std::array<int, D> offset{};
    int rest = t;
    for (int d = 0; d < D; ++d) {
      offset[d] = rest % 3;
      node[d] = b[d] + offset[d];
      rest /= 3;
    }
    visit(grid.linear(node), Vec<D>(grid.position(node) - x), weight<D>(axes, offset));
  }
}

/// for_stencil with the weights of x computed here.
template <int D, class Visit>
void for_stencil(const Grid<D>& grid, const Vec<D>& x, Visit&& visit) {
  for_stencil<D>(grid, x, axis_weights<D>(grid, x), visit);
}

/// q̄_p = Σ_i w_ip q_i with q_i = Σ_p' w_ip' m_p' q_p' / Σ_p' w_ip' m_p' over the particles p' of
/// p's phase. Serial, in particle order (a view, not a step).
template <int D>
std::vector<double> through_grid(const Grid<D>& grid, const Particles<D>& ps, const std::vector<double>& q) {
  std::vector<double> out(ps.size(), 0.0);
  for (const bool sand : {false, true}) {
    std::vector<double> mass(grid.node_count(), 0.0), sum(grid.node_count(), 0.0);
    for (std::size_t p = 0; p < ps.size(); ++p)
      if (ps.is_sand(p) == sand)
        for_stencil<D>(grid, ps.x[p], [&](std::size_t k, const Vec<D>&, double w) {
          mass[k] += w * ps.m[p];
          sum[k] += w * ps.m[p] * q[p];
        });
    for (std::size_t p = 0; p < ps.size(); ++p)
      if (ps.is_sand(p) == sand)
        for_stencil<D>(grid, ps.x[p], [&](std::size_t k, const Vec<D>&, double w) {
          if (mass[k] > 0.0) out[p] += w * sum[k] / mass[k];
        });
  }
  return out;
}

}  // namespace sc::mpm
