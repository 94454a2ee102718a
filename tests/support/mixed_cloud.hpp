// A random cloud of water, sand and wall particles for the tests of the batched pair loops
// (sph/neighbour_batch.hpp).
#pragma once
#include <random>

#include "core/particle_set.hpp"

namespace sc::test {

/// A random cloud of water with sand, slip and rough wall particles among it, about 48 neighbours
/// each; all supports equal (`uniform`) or a third of them larger, so that both paths of the
/// batched pair loops run.
template <int D>
ParticleSet<D> mixed_cloud(unsigned seed, bool uniform) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double h = 0.08, side = D == 3 ? 0.3 : 0.2;
  const int n = D == 3 ? 600 : 380;
  ParticleSet<D> ps;
  for (int k = 0; k < n; ++k) {
    const std::size_t i = ps.append();
    for (int a = 0; a < D; ++a) {
      ps.x[i][a] = side * u(rng);
      ps.v[i][a] = u(rng) - 0.5;
    }
    ps.h[i] = uniform || i % 3 != 0 ? h : 1.25 * h;
    ps.m[i] = 0.01 + 0.02 * u(rng);
    ps.rho[i] = 900.0 + 200.0 * u(rng);
    ps.rho0[i] = 1000.0;
    ps.p[i] = 5000.0 * u(rng);
    if (i % 5 == 1) ps.phase[i] = static_cast<std::uint8_t>(Phase::Sand);
    if (i % 7 == 2) {
      ps.phase[i] = static_cast<std::uint8_t>(Phase::Boundary);
      ps.rough[i] = i % 2;
      ps.v[i] = Vec<D>::Zero();
    }
  }
  return ps;
}

}  // namespace sc::test
