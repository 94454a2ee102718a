// Diffusion of the absorbed water between porous particles (Lenaerts et al. 2008 eqs 8-10).
#pragma once
#include <algorithm>
#include <cmath>

#include "core/types.hpp"
#include "sph/kernels.hpp"

namespace sc {

/// What one particle brings to the exchange of absorbed water in a step.
template <int D>
struct ExchangeSlot {
  Vec<D> x = Vec<D>::Zero();
  Vec<D> pore_velocity = Vec<D>::Zero();  ///< v_p (eq 27) [m/s]
  double mass = 0;       ///< m_p: absorbed water (porous) or the particle's own mass (water) [kg]
  double capacity = 0;   ///< largest m_p it can hold: ρ^f φ V (porous) or a full particle's mass (water)
  double flow_factor = 0;  ///< S^β of eq 29 (1 for water particles, which give water as saturated)
  double volume = 0;     ///< V [m^D] as a receiver (a full particle's volume for water)
  double h = 0;          ///< support radius [m]
  double contact_speed = 0;  ///< > 0 for water in contact with a porous body: it gives at this speed in
                             ///< every direction instead of along v_p (see pair_flow)
  double height = 0;         ///< x·(−ĝ): height against gravity [m]
  bool draws_up = false;     ///< a porous receiver whose suction lifts contact water (see pair_flow)
};

/// Mass flow from `src` to `dst` before limiting [thesis eq. 28] and [thesis eq. 29], in the
/// conserving upwind form 28′ of docs/equations.md (ours [I]), in kg/s:
///   Φ_{j→i} = L_ij · max(0, v_pj · (x_i − x_j)/r) · S_j^β · m_pj · V_i · ∇²W_visc(r, h̄),
/// with h̄ = (h_i + h_j)/2 and L_ij = λ h̄. The net rate of i is Σ_j (Φ_{j→i} − Φ_{i→j}): what one
/// particle gains its neighbour loses, so the water balance is exact.
/// Errata: eq 29 writes v_pi where Lenaerts (eq 9) has v_pj, the source particle's pore velocity;
/// eq 28 (as Lenaerts' eq 8) has no outflow term (not conservative) and lacks a length
/// (kg/(m s), not kg/s), which L_ij supplies. λ is calibrated (flux_length_factor) so that a
/// uniform pore velocity on a lattice carries the water of each site at v_p: the Darcy flux
/// φ S^{β+1} v_p as a water volume (a full water particle per site).
/// Water in contact (src.contact_speed > 0, ours [I]): free water touching a porous body is the
/// pond at the body's surface, which keeps the surface saturated (the boundary condition of
/// ponded infiltration and of a permeameter's inflow face). It gives at contact_speed (one
/// spacing per step, more than any receiver can take) in every direction; the receiver's
/// free-volume limiter then takes exactly what the surface particle has room for, so the
/// infiltration rate is set by the porous body (Darcy) and not by the size or the eq 27 pore
/// velocity of the water particle. Contact water never flows up into a receiver above it unless
/// the receiver's suction exceeds one spacing of water head (draws_up): the water that drips
/// from a seepage face is not drawn back, as the seepage face itself only lets water leave into
/// air below that suction (porous_flow.hpp).
/// Computed by both particles of a pair from the same arguments, so both see the same bits.
template <int D>
inline double pair_flow(const ExchangeSlot<D>& src, const ExchangeSlot<D>& dst, double lambda) {
  if (src.mass <= 0.0) return 0.0;  // the cheap tests first: a dry source gives nothing
  if (src.contact_speed > 0.0 && dst.height > src.height && !dst.draws_up) return 0.0;
  const Vec<D> d = dst.x - src.x;
  const double r = d.norm();
  const double hbar = 0.5 * (src.h + dst.h);
  if (r <= 0.0 || r >= hbar) return 0.0;
  const double u = src.contact_speed > 0.0 ? src.contact_speed : src.pore_velocity.dot(d) / r;
  if (u <= 0.0) return 0.0;
  return lambda * hbar * u * src.flow_factor * src.mass * dst.volume * kernel::viscosity_laplacian<D>(r, hbar);
}

/// The literal eq 28 contribution of neighbour j to ∂m_pi/∂t (Lenaerts' form, documented switch
/// porous.diffusion = "lenaerts_literal"): d_ij V_j m_pj ∇²W(r, h_j) with d_ij = v_pj·x̂_ij S_j^β
/// (eq 29 with Lenaerts' index). Not conservative; the caller clamps m_p to [0, capacity].
template <int D>
inline double literal_rate(const ExchangeSlot<D>& i, const ExchangeSlot<D>& j) {
  const Vec<D> d = j.x - i.x;
  const double r = d.norm();
  if (r <= 0.0) return 0.0;
  const double dij = j.pore_velocity.dot(d) / r * j.flow_factor;
  return dij * j.volume * j.mass * kernel::viscosity_laplacian<D>(r, j.h);
}

/// λ such that L = λ h makes the pair flow of a lattice of spacing dx (support h, every particle of
/// volume V, the porous_volume of its sites) with a uniform pore velocity v carry the water of each
/// site through any lattice plane at v, the mass flux m_p v / dx^D (m_p per site; test
/// porous/diffusion_carries_the_darcy_flux_on_a_lattice):
///   λ = 1 / (h V Σ_{k: k·e > 0} (k·e)²/|k| ∇²W_visc(|k|, h)) = 2D / (h V Σ_{k ≠ 0} |k| ∇²W_visc(|k|, h)).
/// V is the receivers' volume in the pair flows, so it must be the volume porous flow gives its
/// particles (lattice_volume): calibrated on another volume V', the flux would be V/V' of Darcy's.
template <int D>
double flux_length_factor(double dx, double h, double volume) {
  const int reach = static_cast<int>(std::ceil(h / dx)) + 1;
  double sum = 0.0;
  std::array<int, D> k;
  k.fill(-reach);
  while (true) {
    double r2 = 0.0;
    for (int a = 0; a < D; ++a) r2 += (k[a] * dx) * (k[a] * dx);
    const double r = std::sqrt(r2);
    if (r > 0.0) sum += r * kernel::viscosity_laplacian<D>(r, h);
    int a = 0;
    while (a < D && ++k[a] > reach) k[a++] = -reach;
    if (a == D) break;
  }
  return 2.0 * D / (h * volume * sum);
}

/// Scale factors of the limiters of 28′, the free- and occupied-volume checks the thesis states
/// in prose after [thesis eq. 30]: a particle's outflow over dt is at most its water m_p and its
/// inflow at most its free room (capacity − m_p). Each pair flow is scaled by min(out of the
/// source, in of the receiver), so the balance stays exact and 0 ≤ m_p ≤ capacity after the step.
/// A particle that sends nothing keeps scale 1 even when round-off left its m_p a little below
/// zero: the ratio m_p/(outflow dt) would be 0/0 there, and that NaN would spread through the pair
/// flows into new water particles (test
/// porous/limiters_eq_30_stay_finite_for_an_empty_particle_left_below_zero_by_round_off).
inline double outflow_scale(double mass, double outflow, double dt) {
  return outflow > 0.0 && outflow * dt > mass ? std::max(0.0, mass) / (outflow * dt) : 1.0;
}
inline double inflow_scale(double mass, double capacity, double inflow, double dt) {
  const double room = std::max(0.0, capacity - mass);
  return inflow * dt > room ? room / (inflow * dt) : 1.0;
}

/// Explicit Euler step [thesis eq. 30]: m_p ← m_p + Δt ∂m_p/∂t, with the limited rates.
inline double euler_mass(double mass, double inflow, double outflow, double dt) {
  return mass + dt * (inflow - outflow);
}

}  // namespace sc
