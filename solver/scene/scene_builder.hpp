// Builds the particles of a case at a given spacing: lattice blocks of water or sand and the tank walls.
#pragma once
#include <cmath>

#include "core/particle_set.hpp"
#include "case/case_file.hpp"
#include "sph/kernels.hpp"

namespace sc {

/// Mass that makes the summation density (eq 6, kernel k, support h) of an unbounded lattice of
/// spacing dx equal to rho0 exactly: m = ρ0 / Σ_k W(|k dx|, h). This removes the kernel's
/// discretisation bias from the rest state (a lattice at rest spacing has zero pressure).
template <int D>
double lattice_mass(double rho0, double dx, double h, kernel::DensityKernel k);

/// Positions of the lattice points (min + (k + 1/2) dx) inside the box [min, max).
template <int D>
std::vector<Vec<D>, Eigen::aligned_allocator<Vec<D>>> lattice_points(const Vec<D>& min, const Vec<D>& max, double dx);

/// Number of wall-particle layers of a closed tank side: enough to fill the support h of a fluid
/// particle at the wall (ceil(h / dx)).
inline int tank_wall_layers(double h, double dx) { return static_cast<int>(std::ceil(h / dx)); }

/// The values a case fixes at one particle spacing, computed in one place (resolve) for the scene
/// builder, the SPH parameters and the observers.
struct Resolution {
  double dx = 0.0;          ///< particle spacing [m]
  double h = 0.0;           ///< kernel support, support_ratio * dx [m]
  double water_mass = 0.0;  ///< lattice_mass of water at dx [kg]
  double sand_mass = 0.0;   ///< lattice_mass of sand at dx [kg] (0 without a "sand" section)
  int wall_layers = 0;      ///< tank_wall_layers(h, dx)
};

/// The Resolution of `spec` at spacing dx (in the case's dimension).
Resolution resolve(const CaseSpec& spec, double dx);

/// How many particles build_scene would make at spacing dx, found without making them: blocks and
/// tank walls counted from their lattices (as built), each mesh bounded by the lattice of the box it must fit
/// in (the tank, else the domain). A double, so that a mistyped spacing cannot overflow it.
double estimate_particles(const CaseSpec& spec, double dx);

/// The default of `--max-particles`: far above every case of the suite, far below what a mistyped
/// spacing asks for (a dam break at 1e-7 m would need about 3e11 particles).
inline constexpr double kDefaultMaxParticles = 3e7;

/// Throws InputError (the case file, `json_path` of the spacing, the estimate and the flag that
/// raises the limit) when the case at spacing dx would exceed `limit` particles. Called before
/// anything is allocated.
void check_particle_count(const CaseSpec& spec, double dx, double limit, const std::string& json_path);

/// The particles of `spec` at spacing dx: its blocks (in file order; at rest, or spinning rigidly at
/// their angular_velocity about their centre of mass) then its tank walls.
template <int D>
ParticleSet<D> build_scene(const CaseSpec& spec, double dx);

template <int D>
Vec<D> to_vec(const std::vector<double>& v) {
  Vec<D> out;
  for (int d = 0; d < D; ++d) out[d] = v[d];
  return out;
}

}  // namespace sc
