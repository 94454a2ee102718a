// Sand stages of a step: the yield state and frictional stress of every sand particle, and the
// forces on sand (pressure, friction, contact, rough walls). Gather loops: each particle writes
// only its own data, so results do not depend on the number of threads.
#pragma once
#include "core/particle_set.hpp"
#include "neighbours/neighbour_grid.hpp"
#include "sand/rigid_body.hpp"
#include "sand/sand_params.hpp"
#include "sph/gradient_correction.hpp"
#include "water/water_forces.hpp"

namespace sc {

/// Rest spacing of a particle, s = (m/ρ0)^(1/D) [m].
template <int D>
inline double rest_spacing(double m, double rho0) {
  if constexpr (D == 2) return std::sqrt(m / rho0);
  else return std::cbrt(m / rho0);
}

/// The rest spacing of neighbours (rest_spacing, a cube root in 3-D), remembered for the last mass
/// and rest density seen: a particle's wall and water neighbours mostly share both. Same bits.
template <int D>
class NeighbourSpacing {
 public:
  double operator()(double m, double rho0) {
    if (m != m_ || rho0 != rho0_) {
      m_ = m;
      rho0_ = rho0;
      spacing_ = rest_spacing<D>(m, rho0);
    }
    return spacing_;
  }

 private:
  double m_ = -1.0, rho0_ = -1.0, spacing_ = 0.0;
};

/// Pressure that enters friction and yield (eqs 8, 10) [Pa]: the SPH pressure, but at least the
/// weight of half a particle layer, ρ0 |g| s/2. Summation density is deficient at a free surface, so
/// the state equation gives p = 0 on the top layer, where a grain physically carries its own weight
/// (Zhu & Bridson's surface grid cells carry ρ g Δx/2): without it surface grains would feel no
/// friction and the slope of a pile would erode layer by layer. A choice of ours, not in the thesis.
inline double granular_pressure(double p, double rho0, double gravity, double spacing) {
  return std::max(p, 0.5 * rho0 * gravity * spacing);
}

/// For every sand particle: velocity gradient and strain rate (eq 9′) of the velocities the step
/// would produce without friction, v* = v + Δt F/m (as Zhu & Bridson test the velocity after
/// gravity and pressure: a column at rest must still feel that it is about to collapse), the yield
/// test (eq 10) with the rigid stress (eq 12a) for step dt, and the tension-positive stress
/// Σ_i = −σ_f (eq 8) of flowing particles (zero for rigid ones, whose motion is the cluster's).
/// Writes ps.rigid, ps.strain_rate and stress[i] (zero for non-sand particles); `predicted` is the
/// buffer of v* (resized, held by the caller so that a step does not allocate).
/// Wet sand (porous flow): friction and yield use Terzaghi's effective pressure of
/// [thesis eq. 32], p' = max(0, p − η k^p S) with η = stress_scale, k^p = pore_stiffness and the
/// particle's saturation S (solver/porous/effective_stress.hpp); dry sand (S = 0) keeps p. With
/// sand.wet_cohesion_loss the cohesion of the yield test is c0 (1 − S) (solver/porous/wet_cohesion.hpp).
template <int D>
void update_sand_state(ParticleSet<D>& ps, const NeighbourGrid<D>& nb, const SandParams& sand, double gravity,
                       double dt, MatArray<D>& stress, VecArrayOf<D>& predicted, double stress_scale = 0.0,
                       double pore_stiffness = 0.0);

/// Adds the frictional force between sand particles (eq 19′) of the stresses Σ = −σ_f, with the
/// symmetrised kernel-gradient correction (L_i + L_j)/2 of the pressure force when `correction` is
/// filled: the spiky gradient alone underestimates gradients on a lattice at h = 2 dx (test
/// sand/d_ij_eq_20_is_first_order_consistent), which weakens friction by as much and lowers the
/// angle of repose. The pair term stays antisymmetric.
template <int D>
void add_frictional_forces(ParticleSet<D>& ps, const NeighbourGrid<D>& nb, const MatArray<D>& stress,
                           const MatArray<D>& correction);

/// Adds to ps.force of every sand particle: pressure (eq 4, with the gradient correction of the
/// water model so that sand-water pairs are symmetric), viscosity (water's μ against water, the
/// sand viscosity against sand), and Bell contact against
/// water and wall particles. wall_force[i] receives the push of rough wall particles on i (pressure
/// and contact), the normal force of the wall friction. dt is the step the contact must be stable at
/// (contact_law).
template <int D>
void add_sand_forces(ParticleSet<D>& ps, const NeighbourGrid<D>& nb, const SandParams& sand, const WaterParams& water,
                     double sound_speed, double dt, const MatArray<D>& correction, VecArrayOf<D>& wall_force);

/// Adds to ps.force of every water particle the Bell contact force of its sand neighbours (the
/// reaction of the sand-water contact in add_sand_forces).
template <int D>
void add_water_sand_contact(ParticleSet<D>& ps, const NeighbourGrid<D>& nb, const SandParams& sand, double sound_speed,
                            double dt);

/// Adds to ps.force of every partial water particle (is_partial_water of `full_water_mass`: porous
/// exchange) the Bell contact force of its non-porous wall neighbours, with the contact law of sand
/// against walls (ours). A partial particle carries the pressure of the water around it
/// (set_partial_water_pressure), not the stiff pressure of its own compression that holds a full
/// particle off a wall, so without the contact parcels pushed down by the sand would sink through
/// the floor (test sand/partial_water_is_held_off_solid_walls_only). A fixed porous bed takes the
/// parcel in instead.
template <int D>
void add_partial_water_wall_contact(ParticleSet<D>& ps, const NeighbourGrid<D>& nb, const SandParams& sand,
                                    double sound_speed, double dt, double full_water_mass);

/// Adds the Coulomb friction of rough walls (wall_friction_force) to every sand particle pushed by one.
template <int D>
void add_wall_friction(ParticleSet<D>& ps, const VecArrayOf<D>& wall_force, double mu, double dt);

}  // namespace sc
