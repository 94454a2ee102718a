#include "boundary/wall_collision.hpp"

namespace sc {

template <int D>
TankWalls<D> TankWalls<D>::from_tank(const TankSpec& tank, double thickness) {
  TankWalls w;
  w.thickness = thickness;
  for (int d = 0; d < D; ++d) {
    w.extent_min[d] = tank.min[d];
    w.extent_max[d] = tank.max[d];
    for (const int outward : {-1, 1}) {
      if (!tank.closed(d, outward)) continue;
      const double plane = outward < 0 ? tank.min[d] : tank.max[d];
      w.sides.push_back(Side{d, outward, plane, tank.rule(d, outward) == WallRule::NoSlip});
      (outward < 0 ? w.extent_min[d] : w.extent_max[d]) = plane + outward * thickness;
    }
  }
  return w;
}

namespace {

/// Whether the particle that moved from a to b this step hits the side's wall: its path crossed the
/// side's plane from the tank's side, or it ends within the wall's layers, or it started within them
/// (emitted there by the porous flow at a sand particle on the floor) and ends behind the plane,
/// however deep: in its first step the pressure of the wall and of the sand above can drive it
/// through the rest of the layers, where the layers' test alone would no longer catch it (test
/// wall_collision/particle_created_inside_the_floor_layers_and_driven_through_them_is_put_on_the_floor).
/// And the crossing point (or b) lies in front of the wall.
template <int D>
bool hits_wall(const TankWalls<D>& walls, const typename TankWalls<D>::Side& s, const Vec<D>& a, const Vec<D>& b) {
  const int k = s.axis;
  const double depth_a = s.outward * (a[k] - s.position), depth_b = s.outward * (b[k] - s.position);
  if (depth_b <= 0.0) return false;
  Vec<D> hit = b;
  if (depth_a <= 0.0)
    hit = a + ((s.position - a[k]) / (b[k] - a[k])) * (b - a);
  else if (depth_a > walls.thickness && depth_b > walls.thickness)
    return false;
  for (int e = 0; e < D; ++e)
    if (e != k && (hit[e] < walls.extent_min[e] || hit[e] > walls.extent_max[e])) return false;
  return true;
}

}  // namespace

template <int D>
long collide_with_tank(ParticleSet<D>& ps, const TankWalls<D>& walls,
                       const typename ParticleSet<D>::VecArray& x_start) {
  const auto n = static_cast<std::int64_t>(ps.size());
  long collided = 0;
#pragma omp parallel for schedule(static) reduction(+ : collided)
  for (std::int64_t i = 0; i < n; ++i) {
    if (!ps.moves(i)) continue;
    bool hit_any = false;
    for (const auto& s : walls.sides) {
      if (!hits_wall(walls, s, x_start[i], ps.x[i])) continue;
      Vec<D> normal = Vec<D>::Zero();
      normal[s.axis] = s.outward;
      ps.x[i][s.axis] = s.position;
      ps.v[i] = wall_collision_velocity<D>(ps.v[i], normal, s.no_slip);
      hit_any = true;
    }
    if (hit_any) ++collided;
  }
  return collided;
}

template struct TankWalls<2>;
template struct TankWalls<3>;
template long collide_with_tank<2>(ParticleSet<2>&, const TankWalls<2>&, const ParticleSet<2>::VecArray&);
template long collide_with_tank<3>(ParticleSet<3>&, const TankWalls<3>&, const ParticleSet<3>::VecArray&);

}  // namespace sc
