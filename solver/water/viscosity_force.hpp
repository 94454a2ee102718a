// Viscosity force between two particles of unequal supports.
#pragma once
#include "sph/kernels.hpp"
#include "sph/lattice_sum.hpp"

namespace sc {

/// The factor μ V_i V_j ∇̄²W of (v_j − v_i) in f_ij, for the averaged Laplacian `lap` [thesis eq. 5].
inline double viscosity_pair_coefficient(double mu, double Vi, double Vj, double lap) { return mu * Vi * Vj * lap; }

/// Viscosity force on particle i from j [thesis eq. 5] (Müller 2003), in newtons:
///   f_ij = μ V_i V_j (v_j − v_i) (∇²W_visc(r, h_i) + ∇²W_visc(r, h_j))/2.
/// Correct as printed; symmetric in i and j, so f_ji = −f_ij, and it only damps relative motion.
/// `mu` [Pa s] is the viscosity the pair force carries: the case's μ divided by the lattice's
/// viscosity moment (WaterParams::pair_viscosity), so that Σ_j f_ij = μ V_i ∇²v on the case's
/// lattice. `si`: the support h_i.
template <int D>
inline Vec<D> viscosity_pair_force(double mu, double Vi, double Vj, const Vec<D>& vi, const Vec<D>& vj,
                                   double r, const kernel::Support<D>& si, double hj) {
  const double lap = kernel::pair_average([r](const kernel::Support<D>& s) { return kernel::viscosity_laplacian<D>(r, s); }, si, hj);
  return viscosity_pair_coefficient(mu, Vi, Vj, lap) * (vj - vi);
}

/// The viscosity moment of a particle inside a resting lattice block: what eq 5 yields for μ∇²v,
/// as a fraction of the exact value, for any field whose second derivatives are uniform.
/// For v = a y² (one coordinate y), Σ_j V_j (v_j − v_i) ∇²W(r_j) = a Σ_j V_j y_j² ∇²W(r_j), and the
/// exact μ∇²v is 2a μ, so the moment is Σ_j V_j y_j² ∇²W_visc(r_j) / 2 with V_j = 1/Σ_k W_kind(r_k)
/// in units of dx^D (the masses of scene/scene_builder.hpp lattice_mass give the lattice its rest
/// density by the density kernel `kind`). The continuum's moment is 1 (∇²W_visc and ∇W_visc
/// vanish at the support's edge); the lattice's falls short of it: by about 30 % in 2-D at
/// h = 2 dx with the spiky density kernel. Independent of dx; h = support_ratio dx.
template <int D>
double viscosity_moment(double support_ratio, kernel::DensityKernel kind) {
  const double h = support_ratio;  // in units of dx
  const double density = lattice_density_sum<D>(1.0, h, kind);
  const double moment = lattice_sum<D>(1.0, h, [&](const Vec<D>& d, double r) {
    return d[0] * d[0] * kernel::viscosity_laplacian<D>(r, h);
  });
  return moment / (2.0 * density);
}

}  // namespace sc
