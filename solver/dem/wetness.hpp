// Wetness propagation between grains [Rungjiratananon 2008: wetness propagation, fixed]: an
// over-wet grain (w_i > w_f) passes its excess to the touching grains that are not over-wet,
//   w_j ← w_j + k_p Δt (w_i − w_f)/N_i  for each of its N_i drier neighbours,
// and, unlike the seed's write-up, the same water is taken from the source, so the water held by
// all grains is conserved (to round-off; exactly unchanged with k_p = 0). Counted in kilograms.
#pragma once
#include "neighbours/cell_grid.hpp"
#include "dem/grains.hpp"

namespace sc::dem {

/// Moves water from over-wet grains to their touching drier neighbours (gather: each grain sums
/// what it gives and receives in the grid's fixed order). `grid` must be binned on the current
/// positions. Requires k_p Δt <= 1.
template <int D>
void propagate_wetness(Grains<D>& g, const CellGrid<D>& grid, const Params& p, double dt);

}  // namespace sc::dem
