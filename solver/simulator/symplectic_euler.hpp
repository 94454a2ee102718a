// The time integration of a free particle (one not moved as part of a rigid sand cluster).
#pragma once
#include "water/water_forces.hpp"

namespace sc {

/// Symplectic (semi-implicit) Euler step of one particle: v_{n+1} = d (v_n + Δt F_n/m),
/// then x_{n+1} = x_n + Δt v_{n+1} with the new velocity. d is the start-up damping factor
/// (SimulationParams::relax_until; 1 afterwards). Tests: integrator/free_fall_matches_the_discrete_solution,
/// integrator/linear_spring_matches_the_discrete_solution, integrator/start_up_damping_scales_the_new_velocity.
template <int D>
inline void symplectic_euler_step(Vec<D>& x, Vec<D>& v, const Vec<D>& force, double m, double dt, double damping) {
  v = damping * (v + dt * acceleration<D>(force, m));
  x += dt * v;
}

}  // namespace sc
