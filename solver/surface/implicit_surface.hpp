// The implicit surface of a particle set after Zhu & Bridson 2005 ("Animating Sand as a Fluid",
// slides 35-37: "Surface Reconstruction from Particles"). Blobbies (a sum of kernels) bulge on flat
// sand; Zhu & Bridson instead measure the distance to a sphere around the kernel-weighted mean of
// the nearby particles, which keeps a flat layer flat and a lone particle a sphere. The same
// function places FLIP's free surface (flip/transfer.cpp air_distance) and builds the surface
// meshes (surface/surface_mesh.hpp).
#pragma once
#include "core/types.hpp"

namespace sc::surface {

/// Zhu & Bridson's kernel k(s) = max(0, (1 − s²)³), given s² = |x − x_i|²/R².
inline double surface_kernel(double s2) { return s2 >= 1.0 ? 0.0 : (1.0 - s2) * (1.0 - s2) * (1.0 - s2); }

/// φ(x) = |x − x̄| − r̄ at a point x [Zhu-Bridson 2005: Surface Reconstruction], with
/// x̄ = Σ k_i x_i / Σ k_i and r̄ = Σ k_i r_i / Σ k_i over the particles i, k_i = k(|x − x_i|/R),
/// k(s) = max(0, (1 − s²)³), R the neighbourhood (Zhu & Bridson: twice the mean particle spacing).
/// Negative inside, positive outside. Particles are added one by one, so that a caller gathering
/// them in a fixed order gets bitwise the same φ with any number of threads.
template <int D>
class SurfaceAverage {
 public:
  SurfaceAverage(const Vec<D>& at, double reach) : at_(at), reach_(reach) {}

  /// Adds particle x of radius r if it lies within the neighbourhood.
  void add(const Vec<D>& x, double r) {
    const double w = surface_kernel((x - at_).squaredNorm() / (reach_ * reach_));
    if (w == 0.0) return;
    w_sum_ += w;
    x_sum_ += w * x;
    r_sum_ += w * r;
  }
  /// Whether no particle lies within the neighbourhood (φ undefined: far outside).
  bool empty() const { return w_sum_ == 0.0; }
  double phi() const { return (at_ - x_sum_ / w_sum_).norm() - r_sum_ / w_sum_; }

 private:
  Vec<D> at_;
  double reach_;
  double w_sum_ = 0.0, r_sum_ = 0.0;
  Vec<D> x_sum_ = Vec<D>::Zero();
};

/// Zhu & Bridson fix every particle radius to one constant and the neighbourhood to twice the mean
/// spacing s. The constant here follows from what a particle stands for, the cube of side s around
/// it: a simple cubic lattice of spacing s should have its flat surface where those cubes end, half
/// a spacing beyond its outer particle centres. On that plane x̄ lies a little inside the outer
/// layer (the kernel reaches the second one), so φ = 0 there needs r = |x − x̄|, whose mean over the
/// plane is 0.545 s for R = 2s (test surface/lattice_radius_puts_a_flat_face_where_the_cubes_end).
inline constexpr double lattice_radius_factor = 0.545;
inline constexpr double reach_factor = 2.0;  ///< R over s

}  // namespace sc::surface
