// Velocity extrapolation from the fluid into the air around it (Zhu & Bridson 2005), so that
// particles near the free surface interpolate and advect through meaningful face velocities.
#pragma once
#include <vector>

#include "flip/mac_grid.hpp"

namespace sc::flip {

/// The faces whose velocity the solve defines: wall faces and faces next to a fluid cell.
template <int D>
FaceField<D> known_faces(const MacGrid<D>& grid, const std::vector<Cell>& label);

/// Extends u from the known faces into `layers` rings of unknown faces [Zhu-Bridson 2005: Solving on
/// the Grid] ("extend the new velocity field"): each ring takes, per face, the mean of its known
/// neighbours of the same component (a Jacobi sweep from a copy: independent of the visiting order);
/// faces still unknown after the last ring are set to 0. The paper extends with fast sweeping of
/// ∇u·∇φ = 0; the ring average is the same constant extension along the surface normal to first
/// order for one or two cells, which is all the particles reach within one CFL-limited step.
template <int D>
void extrapolate(const MacGrid<D>& grid, FaceField<D> known, int layers, FaceField<D>& u);

}  // namespace sc::flip
