// Collision of moving particles with the planar walls of the box tank: the last line of defence
// behind the wall particles' pressure and contact forces.
//
// Müller, Charypar & Gross 2003 ("Particle-Based Fluid Simulation for Interactive Applications",
// SCA) keep their particles in a box by collision detection and response: a particle that has
// crossed a container wall during the step is put back onto the wall at the contact point and the
// velocity component normal to the wall is removed or reflected (restitution c_R; Müller et al. 2004,
// "Interaction of Fluids with Deformable Solids", scale it with the penetration depth). We use the
// perfectly inelastic response (c_R = 0) so the wall never adds kinetic energy, and the side's wall
// rule for the tangential part: a slip wall keeps it, a no-slip (rough) wall takes it (the wall is at
// rest). The contact plane is the wall's face (the tank's side), half a spacing in front of the first
// layer of wall particles: a plane one particle radius further in (where the first fluid layer rests)
// would also catch the ordinary flow along the floor and, with the no-slip rule, hold back the front
// of a dam break and the runout of a granular collapse. With wall particles in front of every closed
// side, a particle only reaches the plane when the pressure of a thin, fast sheet of water is too
// weak to stop it within one fixed step (test
// wall_collision/thrown_particle_never_leaves_a_slip_box_and_only_loses_energy).
#pragma once
#include <string>
#include <vector>

#include "core/particle_set.hpp"
#include "io/scene_spec.hpp"

namespace sc {

/// The closed sides of a box tank as planes x[axis] = position, and the extent of their walls.
template <int D>
struct TankWalls {
  struct Side {
    int axis = 0;
    int outward = 1;        ///< +1: the side at tank.max (normal +e_axis), −1: at tank.min
    double position = 0.0;  ///< [m] the plane (tank.min or tank.max on the axis)
    bool no_slip = false;
  };
  std::vector<Side> sides;
  double thickness = 0.0;  ///< [m] of the wall-particle layers behind each closed side's plane
  /// Extent of the walls: the tank box widened by the wall thickness on every closed side (open
  /// sides end at the tank's face, e.g. walls of an open-top tank end at its rim).
  Vec<D> extent_min, extent_max;

  /// Walls of the case's tank whose layers are `thickness` [m] thick; no tank: no walls.
  static TankWalls from_tank(const TankSpec& tank, double thickness);
};

/// Velocity after a perfectly inelastic collision with a wall of outward normal n: the outward
/// normal component is removed (an inward one is kept), and on a no-slip wall the tangential one too.
template <int D>
Vec<D> wall_collision_velocity(const Vec<D>& v, const Vec<D>& n, bool no_slip) {
  const double vn = v.dot(n);
  if (no_slip) return vn < 0.0 ? Vec<D>(vn * n) : Vec<D>::Zero();
  return vn > 0.0 ? Vec<D>(v - vn * n) : v;
}

/// For every moving particle (water and sand) whose path from x_start[i] (its position before the
/// step) to its new position crossed a closed side's plane from inside the tank, or that started
/// within the side's wall layers (a particle created there) and ends behind the plane, at a point in
/// front of that side's wall: the
/// particle is put on the plane and its velocity gets the side's collision rule
/// (wall_collision_velocity). Sides are handled in order (x, y, z), so a particle driven into a
/// corner ends in the corner. A particle that went over the rim of an open-top wall is left alone.
/// Each particle writes only itself (deterministic at any thread count); masses are not touched, so
/// the water balance is unchanged. Returns the number of particles put back.
template <int D>
long collide_with_tank(ParticleSet<D>& ps, const TankWalls<D>& walls,
                       const typename ParticleSet<D>::VecArray& x_start);

}  // namespace sc
