// Pressure of wall (boundary) particles, extrapolated from the fluid (Adami, Hu & Adams 2012).
#pragma once
#include "core/particle_set.hpp"
#include "neighbours/neighbour_grid.hpp"
#include "sph/equation_of_state.hpp"

namespace sc {

/// For every boundary particle w with fluid neighbours f (Adami, Hu & Adams 2012, eq 27, static
/// walls):  P_w = (Σ_f P_f W_wf + g · Σ_f ρ_f (x_w − x_f) W_wf) / Σ_f W_wf,
/// and ρ_w from the inverse state equation, so fluid near a wall feels the hydrostatic pressure
/// continued into the wall. Walls with no fluid neighbour get P_w = 0 and ρ_w = ρ0.
template <int D>
void extrapolate_wall_pressure(ParticleSet<D>& ps, const NeighbourGrid<D>& nb, const Vec<D>& gravity,
                               const EquationOfState& eos);

}  // namespace sc
