// Sums over a square (cubic in 3-D) lattice: what a particle in the interior of a resting block of
// lattice particles sees of its neighbours. The particles' masses (scene/scene_builder.hpp
// lattice_mass) and the band of the gradient correction (sph/gradient_correction.hpp full_moment)
// are calibrated on such sums.
#pragma once
#include <array>
#include <cmath>

#include "core/types.hpp"

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

}  // namespace sc
