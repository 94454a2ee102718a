// Sums over a square (cubic in 3-D) lattice: what a particle in the interior of a resting block of
// lattice particles sees of its neighbours. The particles' masses (scene/scene_builder.hpp
// lattice_mass), the band of the gradient correction (sph/gradient_correction.hpp full_moment) and
// eq 5's viscosity moment (water/viscosity_force.hpp viscosity_moment) are calibrated on such sums.
#pragma once
#include <array>
#include <cmath>

#include "core/types.hpp"
#include "sph/kernels.hpp"

namespace sc {

/// Σ term(d, r) over the lattice offsets d = k dx (k integer, every |k_a| ≤ ceil(h/dx) + 1, which
/// covers the support h; the offset 0 included) with r = |d|.
template <int D, class Term>
double lattice_sum(double dx, double h, Term term) {
  const int reach = static_cast<int>(std::ceil(h / dx)) + 1;
  double sum = 0.0;
  std::array<int, D> k;
  k.fill(-reach);
  while (true) {
    Vec<D> d;
    double r2 = 0.0;
    for (int a = 0; a < D; ++a) {
      d[a] = k[a] * dx;
      r2 += d[a] * d[a];
    }
    sum += term(d, std::sqrt(r2));
    int a = 0;
    while (a < D && ++k[a] > reach) k[a++] = -reach;
    if (a == D) return sum;
  }
}

/// Σ_k W_kind(r_k, h) over the lattice offsets of spacing dx (lattice_sum): the summation density
/// [thesis eq. 6] per unit particle mass of a particle inside a resting lattice block, by the
/// density kernel `kind`. A lattice particle's volume is its inverse (scene/scene_builder.hpp
/// lattice_mass gives the lattice its rest density so).
template <int D>
double lattice_density_sum(double dx, double h, kernel::DensityKernel kind) {
  return lattice_sum<D>(dx, h, [&](const Vec<D>&, double r) { return kernel::density_kernel<D>(kind, r, h); });
}

}  // namespace sc
