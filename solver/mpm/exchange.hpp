// What the sand and the water grids of two-grid MPM trade: the momentum exchange of Tampubolon et
// al. 2017, where both phases have mass on a node a drag ξ (v_w − v_s) acts on the sand and its
// negative on the water, taken implicitly so that any ξ Δt is stable; and the pore pressure, shared
// between the phases by their volume fractions (docs/equations.md §9).
#pragma once
#include <algorithm>

#include "core/types.hpp"

namespace sc::mpm {

/// The drag coefficient per unit mixture volume that gives Darcy's law in a steady seepage,
/// c_E = n² ρ_w g / K [kg m⁻³ s⁻¹] (porosity n, water density ρ_w, gravity g, hydraulic conductivity
/// K [m/s]): the water's momentum balance n ρ_w g i = c_E (v_w − v_s) with the Darcy flux
/// q = n (v_w − v_s) gives q = K i for a hydraulic gradient i. [Tampubolon 2017: drag c_E]
inline double drag_per_volume(double porosity, double water_density, double g, double conductivity) {
  return porosity * porosity * water_density * g / conductivity;
}

/// The water saturation of a node, the water volume over the pore volume of the sand there:
/// s_i = min(1, V_i^w / (n V_i^s)), V^α the nodal sums Σ_p w_ip V_p^α; 0 without sand.
/// (A volume fraction, not an indicator of where the two grids overlap.) [Tampubolon 2017: saturation]
inline double node_saturation(double sand_volume, double water_volume, double porosity) {
  return sand_volume > 0.0 ? std::min(1.0, water_volume / (porosity * sand_volume)) : 0.0;
}

/// The drag coefficient of a node [kg/s]: ξ_i = c_E s_i V_i^s n_i/n, for a node of porosity n_i
/// (node_porosity) in sand of porosity n. Darcy's law ties the drag to the flux: per unit volume of
/// saturated bed it is (n ρ_w g/K) q = (c_E/n) q, with q = n_i (v_w − v_s) the flux through the node.
/// Inside a bed n_i = n, and ξ_i = c_E s_i V_i^s: the mixture volume the node's sand represents, in
/// the share of its pores the water fills. On a node across a bed's surface the one water velocity is
/// the mass average of the pore water and the open water, n/n_i of the pore velocity; n_i/n puts the
/// drag back on the pore water's velocity, so that the bed resists over its whole length and not
/// over that less a smoothed layer at each surface. [Tampubolon 2017: nodal drag ξ]
inline double node_drag(double drag_per_volume, double sand_volume, double saturation, double node_porosity,
                        double porosity) {
  return drag_per_volume * saturation * sand_volume * node_porosity / porosity;
}

/// Sand and water velocities of one node after the implicit exchange. With a = Δt ξ, the two rows
///   (m_s + a) v_s − a v_w = m_s ṽ_s,   −a v_s + (m_w + a) v_w = m_w ṽ_w
/// (the same 2x2 matrix for every component) are solved by Cramer's rule: the total momentum is
/// kept exactly and the relative velocity falls by 1/(1 + a (1/m_s + 1/m_w)).
/// [Tampubolon 2017: eq. 22, implicit momentum exchange]
template <int D>
void exchange_momentum(double m_s, double m_w, double a, Vec<D>& v_s, Vec<D>& v_w) {
  const Vec<D> p_s = m_s * v_s, p_w = m_w * v_w;
  const double det = (m_s + a) * (m_w + a) - a * a;
  v_s = ((m_w + a) * p_s + a * p_w) / det;
  v_w = (a * p_s + (m_s + a) * p_w) / det;
}

/// The water velocity of a node whose sand a clamp holds at rest: exchange_momentum in the limit
/// m_s → ∞ with v_s = 0, (m_w + a) v_w = m_w ṽ_w. The water's velocity falls by m_w/(m_w + a) per
/// step, and under a steady force f (so ṽ_w = v_w + Δt f/m_w) it settles where the drag balances
/// it, ξ v_w = f: Darcy's law through a fixed skeleton. [Tampubolon 2017: eq. 22, immovable sand]
template <int D>
void exchange_with_clamped_sand(double m_w, double a, Vec<D>& v_w) {
  v_w *= m_w / (m_w + a);
}

/// The porosity of a node, n_i = 1 − (1 − n) min(1, V_i^s / V_i^m) V_i^s / V_i^{sJ}: V_i^s = Σ_p w_ip V_p⁰
/// and V_i^{sJ} = Σ_p w_ip J_p V_p⁰ of the sand (porosity n undeformed), V_i^m = Σ_p w_ip J_p V_p⁰ / n_p
/// the mixture volume the water's particles fill. The grains are incompressible, so a skeleton at
/// volume ratio J has the porosity 1 − (1 − n)/J (V^s/V^{sJ}: compressed, it has less pore space and
/// squeezes its water, Terzaghi's consolidation); min(1, V^s/V^m) is the share of the node's mixture
/// that is bed: 1 inside a bed, saturated or not, less across a bed's surface, where open water
/// fills the rest (and the same on a wall, where the sums lose the same share). So n_i is the
/// skeleton's porosity in a bed, 1 in open water and 1 without water. The pore pressure's force on
/// the node's mixture, −∇p, is shared by these fractions: n_i to the water and 1 − n_i to the grains,
/// so sand under still water carries its buoyant weight and a seepage drags the grains by the drag
/// alone. [Zienkiewicz & Shiomi 1984: u-U equations, volume fractions]
inline double node_porosity(double sand_volume, double sand_volume_now, double water_mixture_volume, double porosity) {
  if (!(water_mixture_volume > 0.0) || !(sand_volume > 0.0)) return 1.0;
  return 1.0 - (1.0 - porosity) * std::min(1.0, sand_volume / water_mixture_volume) * (sand_volume / sand_volume_now);
}

/// The pore water stiffens the grains: a skeleton compressed by ε shrinks its pores by (1 − n) ε
/// (incompressible grains, node_porosity), so the pressure rises by K_w (1 − n) ε / n and pushes the
/// grains back with their share 1 − n. Per unit mixture volume the stiffness of (sand, water)
/// displacements is [[E_oed + K_w (1 − n)²/n, K_w (1 − n)], [K_w (1 − n), K_w n]] over the masses
/// (ρ_s, n ρ_w), whose largest eigenvalue is below the trace, c_s² + c_w² (1 + ρ_w (1 − n)²/(n ρ_s))
/// with K_w = ρ_w c_w². This returns the factor of c_w² there. [Zienkiewicz & Shiomi 1984: u-U
/// equations, undrained waves]
inline double mixture_wave_factor(double porosity, double water_density, double sand_density) {
  return 1.0 + water_density * (1.0 - porosity) * (1.0 - porosity) / (porosity * sand_density);
}

}  // namespace sc::mpm
