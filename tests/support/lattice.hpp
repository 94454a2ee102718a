// Test scenes: square lattices of particles with the calibrated lattice mass.
#pragma once
#include "core/particle_set.hpp"
#include "scene/scene_builder.hpp"

namespace sc::test {

/// An n x n lattice of particles of `phase` at spacing dx from the origin, support ratio·dx, with
/// the mass that gives rest density rho0 on an unbounded lattice (spiky density kernel).
inline ParticleSet<2> square_lattice(int n, double dx, double ratio, double rho0, Phase phase) {
  ParticleSet<2> ps;
  const double h = ratio * dx;
  const double m = lattice_mass<2>(rho0, dx, h, kernel::DensityKernel::Spiky);
  for (const auto& x : lattice_points<2>(Vec<2>::Zero(), Vec<2>::Constant(n * dx), dx)) {
    const std::size_t i = ps.append();
    ps.x[i] = x;
    ps.m[i] = m;
    ps.h[i] = h;
    ps.rho0[i] = ps.rho[i] = rho0;
    ps.phase[i] = static_cast<std::uint8_t>(phase);
  }
  return ps;
}

}  // namespace sc::test
