// Velocity extrapolation from the fluid into the air around it (Zhu & Bridson 2005), so that
// particles near the free surface interpolate and advect through meaningful face velocities.
#pragma once
#include <span>
#include <vector>

#include "flip/mac_grid.hpp"

namespace sc::flip {

/// Extends the face velocities of `fields` from the faces next to a fluid cell into the faces within
/// `layers` cell widths of them [Zhu-Bridson 2005: velocity extrapolation] ("extend the new velocity
/// field" by fast sweeping): per component, the distance φ (in cell widths) from those faces by fast
/// sweeping of |∇φ| = 1 (Zhao 2005: Godunov upwind update, the 2^D sweep orders), then the upwind
/// solution of ∇u·∇φ = 0 in the same sweep orders, u = Σ_d w_d u_d / Σ_d w_d over the neighbour
/// of smaller φ along each axis d with w_d = φ − φ_d > 0: a velocity constant along the normal of
/// a flat surface is extended exactly. Faces further than `layers` are set to 0; the tank's wall
/// faces are neither sources nor changed. Each component is one serial task: the result does not
/// depend on the number of threads.
template <int D>
void extrapolate(const MacGrid<D>& grid, const std::vector<Cell>& label, int layers,
                 std::span<FaceField<D>* const> fields);

}  // namespace sc::flip
