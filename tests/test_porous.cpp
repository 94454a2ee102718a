// Porous flow (solver/porous/, Lenaerts et al. 2008 as in thesis §3.4-3.5): saturation
// [thesis eq. 21], capillary gradient [thesis eq. 22], capillary potential [thesis eq. 23],
// porosity [thesis eq. 24], pore pressure [thesis eq. 25], Darcy flux [thesis eq. 26], pore
// velocity [thesis eq. 27], diffusion [thesis eq. 28] with [thesis eq. 29] and [thesis eq. 30],
// wet rest density [thesis eq. 31], effective stress [thesis eq. 32]; absorption, emission, the
// water balance and thread-count independence.
#include <omp.h>

#include <boost/test/unit_test.hpp>

#include "adaptive/split_merge.hpp"
#include "boundary/wall_pressure.hpp"
#include "porous/capillary.hpp"
#include "porous/darcy.hpp"
#include "porous/partial_water_pressure.hpp"
#include "porous/diffusion.hpp"
#include "porous/effective_stress.hpp"
#include "porous/pore_pressure.hpp"
#include "porous/rigid_pore_pressure.hpp"
#include "porous/porous_flow.hpp"
#include "porous/porous_setup.hpp"
#include "porous/porous_volume.hpp"
#include "porous/saturation.hpp"
#include "porous/wet_cohesion.hpp"
#include "porous/wet_density.hpp"
#include "reference/analytic/capillary_rise.hpp"
#include "reference/analytic/green_ampt.hpp"
#include "scene/scene_builder.hpp"
#include "simulator/simulator.hpp"
#include "sph/density.hpp"
#include "sph/gradient_correction.hpp"
#include "water/water_forces.hpp"
#include "support/lattice.hpp"

using namespace sc;

namespace {

constexpr double kDx = 0.01, kRho = 1000.0;

PorousParams test_params() {
  PorousParams p;
  p.porosity = 0.4;
  p.permeability = 1e-8;
  p.capillary_constant = 500.0;
  p.capillary_exponent = 0.5;
  p.saturation_exponent = 3.0;
  derive_porous<2>(p, kDx, 2.0 * kDx, lattice_mass<2>(kRho, kDx, 2.0 * kDx, kernel::DensityKernel::Spiky));
  return p;
}

/// Adds lattice particles of a phase in [lo, hi) at spacing kDx, support 2 kDx, water lattice mass;
/// porous ones at saturation S0.
void add_block(ParticleSet<2>& ps, const PorousParams& p, Phase phase, Vec<2> lo, Vec<2> hi, double S0) {
  ps.add_porous_fields();
  for (const auto& x : lattice_points<2>(lo, hi, kDx)) {
    const std::size_t i = ps.append();
    ps.x[i] = x;
    ps.m[i] = p.water_mass;
    ps.h[i] = p.water_support;
    ps.rho[i] = ps.rho0[i] = kRho;
    ps.phase[i] = static_cast<std::uint8_t>(phase);
    if (phase == Phase::Water) continue;
    ps.porosity[i] = p.porosity;
    ps.absorbed[i] = S0 * kRho * p.porosity * porous_volume(ps, i);
  }
}

/// A fixed porous bed, saturated in its lower half and dry above, with a water blob resting on it
/// and walls on the floor far below: absorption on top, emission into air at the bottom.
Simulator<2> exchange_scene() {
  const PorousParams p = test_params();
  ParticleSet<2> ps;
  add_block(ps, p, Phase::Boundary, {0.0, 0.10}, {0.1, 0.15}, 1.0);
  add_block(ps, p, Phase::Boundary, {0.0, 0.15}, {0.1, 0.20}, 0.0);
  add_block(ps, p, Phase::Water, {0.03, 0.20}, {0.07, 0.24}, 0.0);
  add_block(ps, p, Phase::Boundary, {-0.1, -0.03}, {0.2, 0.0}, 0.0);  // a plain floor (porosity 0)
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (ps.x[i][1] < 0.0) ps.porosity[i] = ps.absorbed[i] = 0.0;
  SimulationParams sp;
  sp.dt_max = 2.5e-4;
  sp.eos.sound_speed = 15.0;
  sp.water.viscosity = 4.0;
  sp.gravity = {0.0, -9.81};
  sp.domain_min = {-1.0, -1.0};
  sp.domain_max = {1.0, 1.0};
  sp.porous = p;
  sp.porous->create_fraction = 0.5;
  return Simulator<2>(std::move(ps), sp);
}

/// A 12 x 12 sand lattice in simple shear v = (rate y, 0) at pressure 4000 Pa, densities computed.
void shear_sand(ParticleSet<2>& ps, NeighbourGrid<2>& nb, double rate) {
  nb.rebuild(ps);
  compute_density(ps, nb, kernel::DensityKernel::Spiky, 1000.0);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    ps.v[i] = Vec<2>(rate * ps.x[i][1], 0.0);
    ps.p[i] = 4000.0;
  }
}

constexpr std::size_t kCentre = 6 * 12 + 6;  ///< an interior particle of the 12 x 12 lattice

/// A water particle's pressure and acceleration in BedFace: the state-equation pressure of its
/// own density at its place, the pressure it takes, its acceleration.
struct State {
  double own, p;
  Vec<2> a;
};

/// A fixed porous bed (x < 0.05, saturated) beside a pond of full water at a uniform 1 kPa, no
/// gravity, and one water particle that drifted into the bed's face while it was a parcel (no
/// stiffness of its own): 0.55 spacings from the bed's first row, as the parcels of capillary_rise
/// at 0.005 m sit. state_at(fraction) gives that particle's State with the given fraction of a full
/// mass (its rest density as porous_flow sets it), the forces of eq 4 with or without the
/// kernel-gradient correction (the band of the spiky lattice at h = 2 dx), and, with it, the
/// parcels' corrections weighted (weight_partial_water_corrections) or not.
struct BedFace {
  PorousParams p = test_params();
  ParticleSet<2> ps;
  NeighbourGrid<2> nb;
  EquationOfState eos;
  std::size_t parcel = 0;

  BedFace() {
    add_block(ps, p, Phase::Boundary, {0.0, 0.0}, {0.05, 0.1}, 1.0);
    add_block(ps, p, Phase::Water, {0.05, 0.0}, {0.12, 0.1}, 0.0);
    parcel = ps.size();
    for (std::size_t i = 0; i < ps.size(); ++i)
      if (ps.phase_of(i) == Phase::Water && std::abs(ps.x[i][0] - 0.055) < 1e-9 && std::abs(ps.x[i][1] - 0.045) < 1e-9)
        parcel = i;
    BOOST_TEST_REQUIRE(parcel < ps.size());
    ps.x[parcel][0] = 0.045 + 0.55 * kDx;
    nb.rebuild(ps);
    eos.sound_speed = 15.0;
  }

  enum class Correction { None, Unweighted, Weighted };
  State state_at(double fraction, Correction correction = Correction::None) {
    const double w0 = kernel::density_kernel<2>(p.density_kernel, 0.0, p.water_support);
    ps.m[parcel] = fraction * p.water_mass;
    ps.rho0[parcel] = partial_water_rest_density(kRho, p.water_mass, ps.m[parcel], w0);
    compute_density(ps, nb, p.density_kernel, kRho);
    for (std::size_t i = 0; i < ps.size(); ++i) {
      ps.force[i].setZero();
      if (ps.moves(i)) ps.p[i] = i == parcel ? eos.pressure(ps.rho[i], ps.rho0[i]) : 1000.0;
    }
    const double own = ps.p[parcel];
    set_partial_water_pressure(ps, nb, p.water_mass);
    set_partial_water_density(ps, p.water_mass, kRho);
    extrapolate_wall_pressure(ps, nb, Vec<2>(Vec<2>::Zero()), eos);
    WaterParams water;
    water.gradient_correction = correction != Correction::None;
    MatArray<2> L;
    if (water.gradient_correction) {
      compute_gradient_corrections(ps, nb, CorrectionBand::of_full_moment(full_moment<2>(2.0, p.density_kernel)), L);
      if (correction == Correction::Weighted) weight_partial_water_corrections(ps, p.water_mass, L);
    }
    add_water_forces(ps, nb, water, L);
    return State{own, ps.p[parcel], Vec<2>(ps.force[parcel] / ps.m[parcel])};
  }
};

}  // namespace

BOOST_AUTO_TEST_SUITE(porous)

BOOST_AUTO_TEST_CASE(saturation_eq_21_full_pores_and_clamp) {
  // [thesis eq. 21] S = m_p/(ρ^f φ V): m_p = ρ^f φ V gives S = 1; clamped to [0, 1].
  BOOST_TEST(saturation(1000.0 * 0.4 * 1e-4, 1000.0, 0.4, 1e-4) == 1.0, boost::test_tools::tolerance(1e-14));
  BOOST_TEST(saturation(0.5 * 1000.0 * 0.4 * 1e-4, 1000.0, 0.4, 1e-4) == 0.5, boost::test_tools::tolerance(1e-14));
  BOOST_TEST(saturation(2.0, 1000.0, 0.4, 1e-4) == 1.0);
  BOOST_TEST(saturation(-1e-9, 1000.0, 0.4, 1e-4) == 0.0);
}

BOOST_AUTO_TEST_CASE(capillary_potential_eq_23_limits_and_monotone) {
  // [thesis eq. 23] P^c(1) = 0, P^c(0) = k^c, decreasing in S; between, k^c (1 − S)^α:
  // 2 (1/4)^(1/2) = 1 and 15000 (1/2)^0.1 = 13995.495 (hand values).
  BOOST_TEST(capillary_potential(1.0, 15000.0, 0.1) == 0.0);
  BOOST_TEST(capillary_potential(0.0, 15000.0, 0.1) == 15000.0);
  BOOST_TEST(capillary_potential(0.75, 2.0, 0.5) == 1.0, boost::test_tools::tolerance(1e-15));
  BOOST_TEST(capillary_potential(0.5, 15000.0, 0.1) == 13995.495, boost::test_tools::tolerance(1e-7));
  double prev = INFINITY;
  for (int k = 0; k <= 100; ++k) {
    const double pc = capillary_potential(k / 100.0, 15000.0, 0.1);
    BOOST_TEST(pc < prev);
    prev = pc;
  }
}

BOOST_AUTO_TEST_CASE(capillary_gradient_eq_22_of_a_linear_field) {
  // [thesis eq. 22] at an interior lattice particle, both forms give the slope of a linear P^c
  // (corrected: to round-off; Lenaerts' printed form: to the moment of the spiky gradient on a
  // lattice at h = 2 dx, Σ V_j gradW_ij ⊗ x_ij ≈ 0.7 I, so within 35 %, same direction).
  const PorousParams p = test_params();
  ParticleSet<2> ps;
  add_block(ps, p, Phase::Boundary, {0.0, 0.0}, {0.1, 0.1}, 0.0);
  NeighbourGrid<2> nb;
  nb.rebuild(ps);
  const Vec<2> slope(300.0, -700.0);
  std::vector<double> A(ps.size());
  std::vector<std::uint8_t> part(ps.size(), 1);
  for (std::size_t i = 0; i < ps.size(); ++i) A[i] = 2000.0 + slope.dot(ps.x[i]);
  const std::size_t c = 5 * 10 + 5;
  const Vec<2> corrected = porous_gradient(ps, nb, A, part, c, PorousGradient::Corrected);
  const Vec<2> literal = porous_gradient(ps, nb, A, part, c, PorousGradient::Lenaerts);
  BOOST_TEST((corrected - slope).norm() / slope.norm() < 1e-9);
  BOOST_TEST((literal - slope).norm() / slope.norm() < 0.35);
  BOOST_TEST(literal.normalized().dot(slope.normalized()) > 0.999);
  // At the block's edges and corners half the neighbourhood is missing: the corrected form still
  // gives the slope to round-off (it subtracts A_i, and M⁻¹ restores the lopsided moment), while
  // the printed form picks up the spurious ~A/h of the missing half (docs/equations.md, eq 22).
  double worst = 0.0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const Vec<2> g = porous_gradient(ps, nb, A, part, i, PorousGradient::Corrected);
    worst = std::max(worst, (g - slope).norm() / slope.norm());
  }
  BOOST_TEST(worst < 1e-9);
  const Vec<2> corner = porous_gradient(ps, nb, A, part, 0, PorousGradient::Lenaerts);
  BOOST_TEST((corner - slope).norm() / slope.norm() > 10.0);
}

BOOST_AUTO_TEST_CASE(porosity_eq_24_falls_under_compression) {
  // [thesis eq. 24] φ = φ0 ρ0/ρ: compression lowers φ; expansion raises it, at most to 1.
  BOOST_TEST(porosity(0.4, 2000.0, 2100.0) < 0.4);
  BOOST_TEST(porosity(0.4, 2000.0, 2000.0) == 0.4);
  BOOST_TEST(porosity(0.8, 2000.0, 1000.0) == 1.0);
}

BOOST_AUTO_TEST_CASE(pore_pressure_eq_25_sign_and_proportional_to_saturation) {
  // [thesis eq. 25] with Lenaerts' ratio: ρ^s > ρ0^s gives P^p > 0, ρ^s = ρ0^s gives 0, P^p ∝ S;
  // the thesis' inverted ratio (switch) turns compression into suction.
  BOOST_TEST(pore_pressure(5e4, 0.5, 2100.0, 2000.0, 7.0) > 0.0);
  BOOST_TEST(pore_pressure(5e4, 0.5, 2000.0, 2000.0, 7.0) == 0.0);
  BOOST_TEST(pore_pressure(5e4, 1.0, 2100.0, 2000.0, 7.0) == 2.0 * pore_pressure(5e4, 0.5, 2100.0, 2000.0, 7.0),
             boost::test_tools::tolerance(1e-14));
  BOOST_TEST(pore_pressure(5e4, 0.5, 2100.0, 2000.0, 7.0, true) < 0.0);
}

BOOST_AUTO_TEST_CASE(darcy_flux_eq_26_vanishes_in_hydrostatic_water) {
  // [thesis eq. 26] ∇P = ρ^f g gives q = 0; without a pressure gradient, q = K_h downwards.
  const Vec<2> g(0.0, -9.81);
  BOOST_TEST(darcy_flux<2>(1e-10, 1e-3, Vec<2>(kRho * g), kRho, g).norm() < 1e-20);
  const Vec<2> q = darcy_flux<2>(1e-10, 1e-3, Vec<2>::Zero(), kRho, g);
  BOOST_TEST(q[1] == -1e-10 * kRho * 9.81 / 1e-3, boost::test_tools::tolerance(1e-14));
}

BOOST_AUTO_TEST_CASE(pore_velocity_eq_27_points_to_drier_particles) {
  // [thesis eq. 27] with capillarity alone (no gravity, no pore pressure) v_p points up ∇P^c,
  // towards drier particles, and is q/φ.
  const Vec<2> grad_c(0.0, 100.0);
  const Vec<2> v = pore_velocity<2>(1e-10, 1e-3, 0.4, Vec<2>::Zero(), grad_c, kRho, Vec<2>::Zero());
  BOOST_TEST(v[1] > 0.0);
  BOOST_TEST(v[1] == 1e-10 / (0.4 * 1e-3) * 100.0, boost::test_tools::tolerance(1e-14));
}

BOOST_AUTO_TEST_CASE(two_particle_diffusion_eq_28_29_direction) {
  // [thesis eq. 28], [thesis eq. 29]: j saturated with v_pj pointing at i: i gains, j loses
  // (the flow is upwind, from j); v_p = 0 gives no transfer.
  ExchangeSlot<2> i, j;
  i.x = Vec<2>(0.0, 0.0);
  j.x = Vec<2>(0.0, 0.01);
  for (auto* s : {&i, &j}) { s->h = 0.02; s->volume = 1e-4; s->capacity = 0.04; }
  j.mass = 0.04; j.flow_factor = 1.0;
  j.pore_velocity = Vec<2>(0.0, -0.1);
  i.pore_velocity = Vec<2>(0.0, -0.1);
  BOOST_TEST(pair_flow(j, i, 0.6) > 0.0);  // j → i
  BOOST_TEST(pair_flow(i, j, 0.6) == 0.0);  // i is dry and its v_p points away from j
  j.pore_velocity.setZero();
  BOOST_TEST(pair_flow(j, i, 0.6) == 0.0);
}

BOOST_AUTO_TEST_CASE(pair_flow_of_unequal_supports_uses_their_mean) {
  // [thesis eq. 28] in the pair form 28′ between particles of unequal supports (adaptive water beside
  // sand, different particle sizes): the flow uses h̄ = (h_i + h_j)/2 in L_ij and in ∇²W, so it is
  // the same whichever side has the larger support, and it is the closed form at h̄.
  ExchangeSlot<2> i, j;
  i.x = Vec<2>(0.0, 0.0);
  j.x = Vec<2>(0.003, 0.012);
  for (auto* s : {&i, &j}) { s->volume = 1e-4; s->capacity = 0.04; }
  j.mass = 0.03; j.flow_factor = 0.7;
  j.pore_velocity = Vec<2>(-0.02, -0.1);
  i.h = 0.02;
  j.h = 0.03;
  const double flow = pair_flow(j, i, 0.6);
  std::swap(i.h, j.h);
  BOOST_TEST(flow > 0.0);
  BOOST_TEST(pair_flow(j, i, 0.6) == flow);
  const Vec<2> d = i.x - j.x;
  const double r = d.norm(), hbar = 0.025, u = j.pore_velocity.dot(d) / r;
  const double closed = 0.6 * hbar * u * 0.7 * 0.03 * 1e-4 * kernel::viscosity_laplacian<2>(r, hbar);
  BOOST_TEST(flow == closed, boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(literal_eq_28_gives_surface_water_a_pore_velocity_as_lenaerts_case_b) {
  // [thesis eq. 28] as printed (porous.diffusion = "lenaerts_literal"): free water next to a dry
  // porous bed takes part as Lenaerts' case B, a saturated porous particle with φ = 1 and S = 1, so
  // [thesis eq. 27] gives it a pore velocity into the bed: at least the gravity drive K ρ^f g/μ
  // downwards, plus the capillary suction of the dry bed. Under 28′ contact water has none.
  const Vec<2> g(0.0, -9.81);
  for (const PorousDiffusion form : {PorousDiffusion::Conserving, PorousDiffusion::LenaertsLiteral}) {
    PorousParams p = test_params();
    p.diffusion = form;
    ParticleSet<2> ps;
    add_block(ps, p, Phase::Boundary, {0.0, 0.0}, {0.1, 0.1}, 0.0);
    add_block(ps, p, Phase::Water, {0.0, 0.1}, {0.1, 0.13}, 0.0);
    NeighbourGrid<2> nb;
    nb.rebuild(ps);
    PorousWork<2> w;
    porous_step(ps, nb, p, g, 1e-4, w);
    const double gravity_drive = p.permeability * kRho * 9.81 / p.fluid_viscosity;
    int checked = 0;
    for (std::size_t i = 0; i < ps.size(); ++i) {
      if (ps.phase_of(i) != Phase::Water || ps.x[i][1] > 0.1 + kDx || std::abs(ps.x[i][0] - 0.055) > 0.02) continue;
      ++checked;
      if (form == PorousDiffusion::Conserving) BOOST_TEST(ps.pore_velocity[i].norm() == 0.0);
      else BOOST_TEST(-ps.pore_velocity[i][1] > gravity_drive);
    }
    BOOST_TEST(checked > 0);
  }
}

BOOST_AUTO_TEST_CASE(diffusion_carries_the_darcy_flux_on_a_lattice) {
  // [thesis eq. 28] in form 28′ with the calibrated length: a uniform pore velocity on a saturated
  // lattice, every receiver of the volume porous flow gives it (porous_volume), carries the water
  // of each site across a plane at v, m_p v / dx² (m_p per site), the mass flux of eqs 26-27.
  const PorousParams p = test_params();
  ParticleSet<2> ps;
  add_block(ps, p, Phase::Boundary, {0.0, 0.0}, {0.2, 0.2}, 1.0);
  const double v = 0.05, m = ps.absorbed[0];
  double flow = 0.0;  // across y = 0.1 through the central 10 columns (x in [0.05, 0.15])
  for (std::size_t a = 0; a < ps.size(); ++a)
    for (std::size_t b = 0; b < ps.size(); ++b) {
      if (!(ps.x[a][1] > 0.1 && ps.x[b][1] < 0.1 && ps.x[a][0] > 0.05 && ps.x[a][0] < 0.15)) continue;
      ExchangeSlot<2> src, dst;
      src.x = ps.x[a]; dst.x = ps.x[b];
      src.h = dst.h = p.water_support;
      src.volume = porous_volume(ps, a);
      dst.volume = porous_volume(ps, b);
      src.mass = m; src.flow_factor = 1.0;
      src.pore_velocity = Vec<2>(0.0, -v);
      flow += pair_flow(src, dst, p.flux_length_factor);
    }
  BOOST_TEST(flow / 0.1 == (m / (kDx * kDx)) * v, boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(limiters_eq_30_keep_mass_and_saturation_in_bounds) {
  // [thesis eq. 30] with the free/occupied-volume limiters: outflow over dt at most m_p, inflow
  // at most the free room, whatever the rates.
  const double mass = 0.01, capacity = 0.04, dt = 1.0;
  const double a = outflow_scale(mass, 5.0, dt), b = inflow_scale(mass, capacity, 7.0, dt);
  BOOST_TEST(euler_mass(mass, 0.0, 5.0 * a, dt) >= -1e-18);
  BOOST_TEST(euler_mass(mass, 7.0 * b, 0.0, dt) <= capacity + 1e-18);
  BOOST_TEST(outflow_scale(mass, 1e-6, dt) == 1.0);
}

BOOST_AUTO_TEST_CASE(limiters_eq_30_stay_finite_for_an_empty_particle_left_below_zero_by_round_off) {
  // [thesis eq. 30]: the Euler step can leave an emptied particle at m_p = −5e-20 kg. With no
  // outflow it has nothing to limit (scale 1, its mass unchanged); with an outflow it sends nothing
  // (scale 0). Either way the scale is finite: a 0/0 here once made new water particles of NaN mass.
  const double mass = -5.42e-20, dt = 1e-3;
  BOOST_TEST(outflow_scale(mass, 0.0, dt) == 1.0);
  BOOST_TEST(outflow_scale(mass, 3.0, dt) == 0.0);
  BOOST_TEST(euler_mass(mass, 0.0, 0.0 * outflow_scale(mass, 0.0, dt), dt) == mass);
}

BOOST_AUTO_TEST_CASE(rigid_pore_pressure_is_linear_in_a_permeameter_and_hydrostatic_on_a_floor) {
  // Incompressible pore water in a rigid saturated column (Darcy, [thesis eq. 26] with ∇·q = 0):
  // pressures 2000 Pa at the top row and 0 at the bottom row give the linear profile in between
  // (the piezometric pressure is harmonic; the no-flow sides do not bend it), to 1e-6 relative.
  // With the bottom rows absent (a no-flow floor) the column is hydrostatic, dP/dz = −ρ^f g.
  const PorousParams p = test_params();
  const Vec<2> g(0.0, -9.81);
  for (const bool floor : {false, true}) {
    ParticleSet<2> ps;
    add_block(ps, p, Phase::Boundary, {0.0, 0.0}, {0.1, 0.2}, 1.0);
    NeighbourGrid<2> nb;
    nb.rebuild(ps);
    std::vector<PressureRole> role(ps.size(), PressureRole::Unknown);
    std::vector<double> P(ps.size(), 0.0);
    const double top = 0.195, bottom = 0.005;
    for (std::size_t i = 0; i < ps.size(); ++i) {
      if (std::abs(ps.x[i][1] - top) < 1e-9) { role[i] = PressureRole::Prescribed; P[i] = 2000.0; }
      if (std::abs(ps.x[i][1] - bottom) < 1e-9) role[i] = floor ? PressureRole::None : PressureRole::Prescribed;
    }
    solve_harmonic_pressure(ps, nb, role, std::vector<double>(ps.size(), 0.0), kRho, g, P);
    for (std::size_t i = 0; i < ps.size(); ++i) {
      if (role[i] != PressureRole::Unknown) continue;
      const double z = ps.x[i][1];
      const double exact = floor ? 2000.0 + kRho * 9.81 * (top - z) : 2000.0 * (z - bottom) / (top - bottom);
      BOOST_TEST(P[i] == exact, boost::test_tools::tolerance(1e-6));
    }
  }
}

BOOST_AUTO_TEST_CASE(rigid_pore_pressure_carries_the_capillary_suction_of_the_front) {
  // Darcy flux of [thesis eq. 27] is driven by the pore-water pressure P^p − P^c (P^c of
  // [thesis eq. 23]), so in a rigid saturated column it is P^p − P^c − ρ^f g·x that is harmonic.
  // Pond 2000 Pa at the top row (P^c 100 Pa there: P^p − P^c = 2000 Pa as the contact sets it),
  // a wetting front at the bottom row (P^p = 0, suction P^c = 240 Pa), a wet zone in between at
  // P^c = 130 Pa: P^p − P^c is linear from 2000 to −240 Pa (1e-6 relative), i.e. the front's
  // suction drives the whole wet zone (the Green-Ampt drive). Ignoring P^c would give P^p linear
  // from 2100 to 0, 240 Pa short at the front and 130 Pa short in the middle.
  const PorousParams p = test_params();
  const Vec<2> g(0.0, -9.81);
  ParticleSet<2> ps;
  add_block(ps, p, Phase::Boundary, {0.0, 0.0}, {0.1, 0.2}, 1.0);
  NeighbourGrid<2> nb;
  nb.rebuild(ps);
  std::vector<PressureRole> role(ps.size(), PressureRole::Unknown);
  std::vector<double> P(ps.size(), 0.0), suction(ps.size(), 130.0);
  const double top = 0.195, bottom = 0.005, u_top = 2000.0, u_front = -240.0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (std::abs(ps.x[i][1] - top) < 1e-9) { role[i] = PressureRole::Prescribed; suction[i] = 100.0; P[i] = u_top + 100.0; }
    if (std::abs(ps.x[i][1] - bottom) < 1e-9) { role[i] = PressureRole::Prescribed; suction[i] = 240.0; P[i] = 0.0; }
  }
  solve_harmonic_pressure(ps, nb, role, suction, kRho, g, P);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (role[i] != PressureRole::Unknown) continue;
    const double z = ps.x[i][1];
    const double exact = u_front + (u_top - u_front) * (z - bottom) / (top - bottom);
    BOOST_TEST(std::abs(P[i] - suction[i] - exact) <= 1e-6 * (u_top - u_front));
  }
}

namespace {

/// A fixed porous bed of 10 columns, saturated in 0.2 <= y < 0.3 and dry below, under three rows
/// of water; its neighbour lists (nothing moves).
ParticleSet<2> ponded_bed(const PorousParams& p, NeighbourGrid<2>& nb) {
  ParticleSet<2> ps;
  add_block(ps, p, Phase::Boundary, {0.0, 0.0}, {0.1, 0.2}, 0.0);
  add_block(ps, p, Phase::Boundary, {0.0, 0.2}, {0.1, 0.3}, 1.0);
  add_block(ps, p, Phase::Water, {0.0, 0.3}, {0.1, 0.33}, 0.0);
  nb.rebuild(ps);
  return ps;
}

/// Largest deviation of the pore-water pressure P^p − P^c (P^c of the saturation after the step,
/// as the next step sees it) of the central column's particles with y >= y_min from the straight
/// line through the two highest of them below the contact row.
double pore_water_pressure_kink(const ParticleSet<2>& ps, const PorousParams& p, double y_min) {
  std::vector<std::pair<double, double>> u;  // (y, P^p − P^c), top first
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (ps.phase_of(i) == Phase::Boundary && std::abs(ps.x[i][0] - 0.055) < 1e-9 && ps.x[i][1] >= y_min &&
        ps.x[i][1] < 0.29)
      u.emplace_back(ps.x[i][1], ps.pore_pressure[i] - capillary_potential(saturation(ps.absorbed[i], kRho, p.porosity, porous_volume(ps, i)),
                                                                        p.capillary_constant, p.capillary_exponent));
  std::sort(u.begin(), u.end(), std::greater<>());
  const double slope = (u[0].second - u[1].second) / (u[0].first - u[1].first);
  double worst = 0.0;
  for (const auto& [y, v] : u) worst = std::max(worst, std::abs(v - (u[0].second + slope * (y - u[0].first))));
  return worst;
}

}  // namespace

BOOST_AUTO_TEST_CASE(a_fast_flow_keeps_the_wet_zone_under_the_pond_pressure) {
  // Ponded infiltration through a rigid bed (porous_step alone, the pond kept 3 rows deep) at a
  // pore velocity of ~0.37 m/s: each step passes ~4 % of a particle's pores through it
  // ([thesis eq. 28]-[thesis eq. 30] with the limiters), and the limiters leave the wet zone that
  // much short of full (S ≈ 0.982 here). After 40 steps:
  // - the surface row's pore-water pressure P^p − P^c is the pond's, ρ^f g (3.5 dx) (1e-9);
  // - the wet zone's P^p − P^c is one straight line (within 1 % of the pond's pressure), and the
  //   Darcy flux through it ([thesis eq. 27]) is the same in every row (1 %): the pore water is
  //   incompressible. Counting a particle saturated by its content at the end of the step (S >=
  //   0.99) instead of by the water it held while passing the step's outflow on would make the
  //   wet zone "unsaturated" (P^p = 0) row by row, with kinks in the pressure and the flux.
  const PorousParams p = test_params();
  const Vec<2> g(0.0, -9.81);
  NeighbourGrid<2> nb;
  ParticleSet<2> ps = ponded_bed(p, nb);
  PorousWork<2> w;
  const double dt = 1e-3;
  for (int step = 0; step < 40; ++step) {
    porous_step(ps, nb, p, g, dt, w);
    for (std::size_t i = 0; i < ps.size(); ++i)
      if (ps.phase_of(i) == Phase::Water) ps.m[i] = p.water_mass;  // a pond of constant depth
  }
  const double pond = kRho * 9.81 * 3.5 * kDx;
  BOOST_TEST(pore_water_pressure_kink(ps, p, 0.22) <= 0.01 * pond);
  double v_min = INFINITY, v_max = 0.0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps.phase_of(i) != Phase::Boundary || std::abs(ps.x[i][0] - 0.055) > 1e-9 || ps.x[i][1] < 0.21) continue;
    if (ps.x[i][1] > 0.29) {
      BOOST_TEST(ps.pore_pressure[i] - ps.capillary[i] == pond, boost::test_tools::tolerance(1e-9));
      continue;
    }
    v_min = std::min(v_min, -ps.pore_velocity[i][1]);
    v_max = std::max(v_max, -ps.pore_velocity[i][1]);
  }
  BOOST_TEST(v_max <= 1.01 * v_min);
}

namespace {

/// A porous bed 30 columns wide and 20 rows high of `phase` (Boundary: a fixed skeleton; Sand: a
/// moving one, at its rest density), with the held water init_porous gives it at saturation S0,
/// and its neighbour lists (nothing moves).
ParticleSet<2> uniform_bed(PorousParams& p, Phase phase, double S0, NeighbourGrid<2>& nb) {
  ParticleSet<2> ps;
  add_block(ps, p, phase, {0.0, 0.0}, {0.3, 0.2}, 0.0);
  p.initial_saturation = S0;
  init_porous(ps, p);
  for (std::size_t i = 0; i < ps.size(); ++i) ps.rho[i] = ps.rho0[i];  // wet sand's held water is in m and ρ0
  nb.rebuild(ps);
  return ps;
}

/// Volume of a water mass as the lattice measures it: a full water particle fills one site, dx^D
/// (the pond depth of the observers and of the pond pressure, porous/rigid_pore_pressure.hpp).
double lattice_water_volume(double mass, const PorousParams& p) { return mass / p.water_mass * kDx * kDx; }

/// Gravity drainage: a uniform_bed of `phase` at S0 = 0.9 without capillarity, before and after
/// one porous_step of 0.1 ms under gravity, and the Darcy flux K_h S0^(β+1) it should carry
/// (K_h = k ρ^f g / μ).
struct Drainage {
  static constexpr double S0 = 0.9, dt = 1e-4, g = 9.81;
  PorousParams p = test_params();
  ParticleSet<2> before, after;
  double darcy_flux = 0.0;

  explicit Drainage(Phase phase) {
    p.capillary_constant = 0.0;
    NeighbourGrid<2> nb;
    before = uniform_bed(p, phase, S0, nb);
    after = before;
    PorousWork<2> w;
    porous_step(after, nb, p, Vec<2>(0.0, -g), dt, w);
    darcy_flux = p.permeability * kRho * g / p.fluid_viscosity * std::pow(S0, p.saturation_exponent + 1.0);
  }
  /// The flux [m/s] of a water mass that crossed the central band (0.1 m wide) in the step.
  double flux(double mass) const { return lattice_water_volume(mass, p) / (0.1 * dt); }
};

}  // namespace

BOOST_AUTO_TEST_CASE(a_saturated_bed_holds_the_same_water_fixed_or_moving) {
  // Saturation [thesis eq. 21] at S = 1: the pores, a fraction φ of every site of the bed, are
  // full of water, φ times the water a full water particle carries in its site. Both a fixed and a
  // moving bed hold exactly that (1e-12 relative).
  for (const Phase phase : {Phase::Boundary, Phase::Sand}) {
    PorousParams p = test_params();
    NeighbourGrid<2> nb;
    const ParticleSet<2> ps = uniform_bed(p, phase, 1.0, nb);
    double held = 0.0;
    for (std::size_t i = 0; i < ps.size(); ++i) held += ps.absorbed[i];
    BOOST_TEST(held / static_cast<double>(ps.size()) == p.porosity * p.water_mass, boost::test_tools::tolerance(1e-12));
  }
}

BOOST_AUTO_TEST_CASE(a_bed_particle_at_the_surface_has_the_pore_volume_of_an_interior_one) {
  // The pore volume in saturation [thesis eq. 21] is φ V with V the particle's rest volume m/ρ0
  // (porous/porous_volume.hpp), not m/ρ: the summation density falls short at a bed's free surface,
  // and the pores there are no larger. A fixed bed at a uniform S0 = 0.5 whose top two rows read
  // 0.8 ρ0, as a summation density does at a surface: after a porous step of 1 ns without gravity
  // or capillarity (no drive, so no flow to speak of) every particle still reads S0, within 1e-9.
  PorousParams p = test_params();
  p.capillary_constant = 0.0;
  NeighbourGrid<2> nb;
  ParticleSet<2> ps = uniform_bed(p, Phase::Boundary, 0.5, nb);
  std::size_t surface = 0;
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (ps.x[i][1] > 0.18) {
      ps.rho[i] = 0.8 * ps.rho0[i];
      ++surface;
    }
  PorousWork<2> w;
  porous_step(ps, nb, p, Vec<2>(Vec<2>::Zero()), 1e-9, w);
  std::size_t off = 0;
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (std::abs(ps.saturation[i] - 0.5) > 0.5e-9) ++off;
  BOOST_TEST(surface == 2u * 30u);
  BOOST_TEST(off == 0u);
}

BOOST_AUTO_TEST_CASE(fixed_and_moving_beds_carry_the_darcy_flux_of_gravity_drainage) {
  // A bed at S = 0.9 without capillarity under gravity alone (unit hydraulic gradient; P^p = 0 in
  // both beds: an unsaturated fixed skeleton, and eq 25 with k^p = 0): Darcy's law with the
  // relative permeability of [thesis eq. 29] gives q = K_h S^(β+1), K_h = k ρ^f g / μ ([thesis eq. 26],
  // [thesis eq. 27], [thesis eq. 28] in form 28′). In one porous_step the water held in the lower
  // half of the central band (m_p and emission stores) grows by what crosses its top; as a water
  // volume (a full water particle per site, as a pond is measured) per width and time it is q,
  // within 2 %, for a fixed and a moving bed alike.
  for (const Phase phase : {Phase::Boundary, Phase::Sand}) {
    const Drainage run(phase);
    const auto lower_band = [](const ParticleSet<2>& ps) {
      double held = 0.0;
      for (std::size_t i = 0; i < ps.size(); ++i)
        if (ps.x[i][0] > 0.1 && ps.x[i][0] < 0.2 && ps.x[i][1] < 0.1) held += ps.absorbed[i] + ps.emit_store[i];
      return held;
    };
    const double q = run.flux(lower_band(run.after) - lower_band(run.before));
    BOOST_TEST_MESSAGE((phase == Phase::Boundary ? "fixed" : "moving") << " q/(K S^(b+1)) = " << q / run.darcy_flux);
    BOOST_TEST(q == run.darcy_flux, boost::test_tools::tolerance(0.02));
  }
}

BOOST_AUTO_TEST_CASE(a_saturated_bed_drains_at_the_darcy_flux) {
  // A saturated bed (S = 1) without capillarity, its bottom row a seepage face, drains under
  // gravity at the Darcy flux of [thesis eq. 26]-[thesis eq. 29] with k_r(1) = 1, q = K_h: its top
  // is open to the air and its face to the atmosphere (P^p = 0 at both, exposure in porous_flow.cpp).
  // Its rows are full, so the inflow limit of [thesis eq. 30] must count the room a particle's own
  // outflow makes within the step (porous_flow.cpp, second inflow limit): with only the room at
  // the start of the step, none, a row takes from the one above only after it has given, and ends
  // each step short of full by a step's flow q Δt/(φ dx) (0.25 % here), which costs β + 1 = 4 times
  // that in relative permeability. Over 20 porous steps of 0.1 ms, the water the bed lost over its
  // central 0.2 m, as a water volume per width and time, is K_h within 0.5 %, for a fixed and a
  // moving bed.
  for (const Phase phase : {Phase::Boundary, Phase::Sand}) {
    PorousParams p = test_params();
    p.capillary_constant = 0.0;
    NeighbourGrid<2> nb;
    ParticleSet<2> ps = uniform_bed(p, phase, 1.0, nb);
    const auto held = [&] {
      double sum = 0.0;
      for (std::size_t i = 0; i < ps.size(); ++i)
        if (ps.x[i][0] > 0.05 && ps.x[i][0] < 0.25) sum += ps.absorbed[i];
      return sum;
    };
    const double held0 = held(), dt = 1e-4, K = p.permeability * kRho * 9.81 / p.fluid_viscosity;
    PorousWork<2> w;
    for (int step = 0; step < 20; ++step) porous_step(ps, nb, p, Vec<2>(0.0, -9.81), dt, w);
    const double q = lattice_water_volume(held0 - held(), p) / (0.2 * 20 * dt);
    BOOST_TEST_MESSAGE((phase == Phase::Boundary ? "fixed" : "moving") << ": q/K_h = " << q / K);
    BOOST_TEST(q == K, boost::test_tools::tolerance(0.005));
  }
}

BOOST_AUTO_TEST_CASE(a_seepage_face_lets_out_the_darcy_flux_that_reaches_it) {
  // The bed of the drainage test above has nothing below it: its bottom row is a seepage face,
  // where the water that arrives leaves into the air (exposure in porous_flow.cpp, the emission
  // store). Under the unit hydraulic gradient the flux leaving it is the Darcy flux inside,
  // q = K_h S^(β+1) ([thesis eq. 26]-[thesis eq. 29]): in one porous_step the bottom row's emission
  // stores over the central band gain, as a water volume per width and time, q within 2 %, for a
  // fixed and a moving bed.
  for (const Phase phase : {Phase::Boundary, Phase::Sand}) {
    const Drainage run(phase);
    double emitted = 0.0;
    for (std::size_t i = 0; i < run.after.size(); ++i)
      if (run.after.x[i][0] > 0.1 && run.after.x[i][0] < 0.2 && run.after.x[i][1] < kDx) emitted += run.after.emit_store[i];
    const double q = run.flux(emitted);
    BOOST_TEST_MESSAGE((phase == Phase::Boundary ? "fixed" : "moving") << " seepage q/(K S^(b+1)) = " << q / run.darcy_flux);
    BOOST_TEST(q == run.darcy_flux, boost::test_tools::tolerance(0.02));
  }
}

BOOST_AUTO_TEST_CASE(a_pond_loses_the_water_volume_its_bed_fills) {
  // Ponded infiltration into a dry fixed bed (porous_step alone, [thesis eq. 28]-[thesis eq. 30]):
  // after 20 steps the water volume the pond lost (a full water particle fills one site) equals
  // the pore volume filled, Σ S φ dx^D over the bed's sites with S of [thesis eq. 21], within 1 %.
  const PorousParams p = test_params();
  const Vec<2> g(0.0, -9.81);
  ParticleSet<2> ps;
  add_block(ps, p, Phase::Boundary, {0.0, 0.0}, {0.1, 0.2}, 0.0);
  add_block(ps, p, Phase::Water, {0.0, 0.2}, {0.1, 0.23}, 0.0);
  NeighbourGrid<2> nb;
  nb.rebuild(ps);
  auto pond = [&] {
    double m = 0.0;
    for (std::size_t i = 0; i < ps.size(); ++i) m += ps.phase_of(i) == Phase::Water ? ps.m[i] : 0.0;
    return m;
  };
  const double pond0 = pond();
  double pond_end = pond0;
  PorousWork<2> w;
  for (int step = 0; step <= 20; ++step) {
    if (step == 20) pond_end = pond();
    porous_step(ps, nb, p, g, 1e-3, w);  // the last call sets S from the water held after step 20
  }
  double filled = 0.0;
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (ps.phase_of(i) == Phase::Boundary) filled += ps.saturation[i] * p.porosity * kDx * kDx;
  BOOST_TEST_MESSAGE("pores filled / pond loss = " << filled / lattice_water_volume(pond0 - pond_end, p)
                     << ", pond loss " << (pond0 - pond_end) / pond0 << " of the pond");
  BOOST_TEST(filled == lattice_water_volume(pond0 - pond_end, p), boost::test_tools::tolerance(0.01));
}

BOOST_AUTO_TEST_CASE(merged_water_beside_a_bed_keeps_its_level_and_the_rest_density_of_full_water) {
  // A merged water particle (level 1: twice the mass and volume of a sampled one, support
  // 2^(1/2) h0 in 2-D) and a sampled one (level 0) resting on a fixed bed with little room left,
  // one exchange step: both stay nearly full at their level, so both keep a rest density within 10 % of rho^f and
  // the merged one stays level 1, so it can split again. Reading the full mass of the sampled
  // particle for every water particle gave the merged one rho^f + m0 W(0, h) (about 1.7 rho^f here),
  // which also read as level 0 from m/rho0.
  const PorousParams p = test_params();
  ParticleSet<2> ps;
  add_block(ps, p, Phase::Boundary, {0.0, 0.0}, {0.2, 0.05}, 0.98);
  const auto add_water = [&](double x, std::uint8_t level) {
    const std::size_t i = ps.append();
    ps.x[i] = {x, 0.05};
    ps.m[i] = std::ldexp(p.water_mass, level);
    ps.h[i] = p.water_support * std::pow(2.0, 0.5 * level);
    ps.rho[i] = ps.rho0[i] = kRho;
    ps.phase[i] = static_cast<std::uint8_t>(Phase::Water);
    ps.level[i] = level;
    return i;
  };
  const std::size_t merged = add_water(0.05, 1), sampled = add_water(0.15, 0);
  NeighbourGrid<2> nb;
  nb.rebuild(ps);
  PorousWork<2> w;
  porous_step(ps, nb, p, Vec<2>(0.0, -9.81), 1e-5, w);
  BOOST_TEST(ps.m[merged] > 1.9 * p.water_mass);
  BOOST_TEST(ps.m[sampled] > 0.9 * p.water_mass);
  BOOST_TEST(std::abs(ps.rho0[merged] - kRho) < 0.1 * kRho);
  BOOST_TEST(std::abs(ps.rho0[sampled] - kRho) < 0.1 * kRho);
  BOOST_TEST(ps.level[merged] == 1);
  AdaptiveParams levels;
  levels.finest_volume = p.water_mass / kRho;
  BOOST_TEST((decide<2>(0.0, ps.level[merged], levels) == Decision::Split));
  BOOST_TEST(!is_partial_water(ps, merged, p.water_mass));  // nearly full at its level
  ps.m[merged] = 0.9 * p.water_mass;  // the mass of a nearly full level-0 particle: partial at level 1
  BOOST_TEST(is_partial_water(ps, merged, p.water_mass));
}

BOOST_AUTO_TEST_CASE(pond_pressure_is_the_weight_of_the_water_column) {
  // A column of n full water particles over a porous particle: the k-th from the top carries
  // ρ^f g s (k + 1/2); a second column separated by a gap carries only itself.
  const PorousParams p = test_params();
  ParticleSet<2> ps;
  add_block(ps, p, Phase::Water, {0.0, 0.0}, {0.01, 0.05}, 0.0);
  add_block(ps, p, Phase::Water, {0.0, 0.08}, {0.01, 0.1}, 0.0);
  const std::vector<double> P = water_column_pressure(ps, kDx, p.water_mass, kRho, 9.81);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const double top = ps.x[i][1] > 0.07 ? 0.095 : 0.045;
    const double k = std::round((top - ps.x[i][1]) / kDx);
    BOOST_TEST(P[i] == kRho * 9.81 * kDx * (k + 0.5), boost::test_tools::tolerance(1e-12));
  }
}

BOOST_AUTO_TEST_CASE(a_gap_that_water_beside_fills_does_not_cut_the_column) {
  // A pond three columns wide and ten rows deep whose middle column misses two particles (rows
  // 5 and 6 from the top, the gaps a disordered pond leaves in a column one spacing wide): the
  // water beside the hole carries the weight on, so each middle particle carries the middle
  // particles above it, ρ^f g s (k + 1/2), the four above the hole included; a column with no
  // water beside its gap (pond_pressure_is_the_weight_of_the_water_column) still ends there.
  const PorousParams p = test_params();
  ParticleSet<2> ps;
  add_block(ps, p, Phase::Water, {0.0, 0.0}, {0.01, 0.1}, 0.0);
  add_block(ps, p, Phase::Water, {0.02, 0.0}, {0.03, 0.1}, 0.0);
  add_block(ps, p, Phase::Water, {0.01, 0.0}, {0.02, 0.04}, 0.0);
  add_block(ps, p, Phase::Water, {0.01, 0.06}, {0.02, 0.1}, 0.0);
  const std::vector<double> P = water_column_pressure(ps, kDx, p.water_mass, kRho, 9.81);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    double k = 0.0;  // particles above i in its column
    for (std::size_t j = 0; j < ps.size(); ++j)
      k += std::abs(ps.x[j][0] - ps.x[i][0]) < 0.5 * kDx && ps.x[j][1] > ps.x[i][1];
    BOOST_TEST(P[i] == kRho * 9.81 * kDx * (k + 0.5), boost::test_tools::tolerance(1e-12));
  }
}

// The 3-D pond: a column's gap is bridged by water in any of the 3^2 columns around it (its own and
// the 8 beside). Three columns in a row along y, ten rows deep, s = 0.01 m, full particles of
// mass ρ^f s³: the first two miss their particles of rows 5 and 6 from the top, the third is full.
// The full third column beside the second's hole carries the weight on, so every particle of the
// second carries all the particles above it in its column, ρ^f g s (k + 1/2); the first, with only
// the holed second beside it (the third is two columns away), ends at its hole: its particles below
// the hole carry only those below the hole; the third has no gap. To 1e-12.
BOOST_AUTO_TEST_CASE(a_gap_that_water_beside_fills_does_not_cut_a_3d_column) {
  const double s = kDx, m = kRho * s * s * s;
  ParticleSet<3> ps;
  for (int col = 0; col < 3; ++col)
    for (int row = 0; row < 10; ++row) {
      if (col < 2 && (row == 4 || row == 5)) continue;  // the hole: z = 0.045 and 0.055
      const std::size_t i = ps.append();
      ps.x[i] = Vec<3>(0.5 * s, (col + 0.5) * s, (row + 0.5) * s);
      ps.m[i] = m;
      ps.phase[i] = static_cast<std::uint8_t>(Phase::Water);
    }
  const std::vector<double> P = water_column_pressure(ps, s, m, kRho, 9.81);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const bool cut = ps.x[i][1] < s && ps.x[i][2] < 0.04;  // first column, below its hole
    double k = 0.0;  // particles above i in its column that it carries
    for (std::size_t j = 0; j < ps.size(); ++j)
      k += std::abs(ps.x[j][1] - ps.x[i][1]) < 0.5 * s && ps.x[j][2] > ps.x[i][2] && !(cut && ps.x[j][2] > 0.04);
    BOOST_TEST(P[i] == kRho * 9.81 * s * (k + 0.5), boost::test_tools::tolerance(1e-12));
  }
}

BOOST_AUTO_TEST_CASE(wet_rest_density_eq_31) {
  // [thesis eq. 31] dry gives ρ0; a saturated bulk gives ρ0 + φ ρ^f.
  BOOST_TEST(wet_rest_density(1600.0, 0.0, 0.4, 1000.0) == 1600.0);
  BOOST_TEST(wet_rest_density(1600.0, 1.0, 0.4, 1000.0) == 2000.0);
}

namespace {

constexpr double kSandDensity = 1600.0;  // dry bulk rest density of the test sand [kg/m^3]

/// Dry sand lattice in [lo, hi) (lattice mass of kSandDensity, support 2 kDx), its pores filled to
/// S0 by init_porous as the scene builder does.
ParticleSet<2> wet_sand(const PorousParams& p, Vec<2> lo, Vec<2> hi, double S0) {
  ParticleSet<2> ps;
  for (const auto& x : lattice_points<2>(lo, hi, kDx)) {
    const std::size_t i = ps.append();
    ps.x[i] = x;
    ps.m[i] = lattice_mass<2>(kSandDensity, kDx, 2.0 * kDx, kernel::DensityKernel::Spiky);
    ps.h[i] = p.water_support;
    ps.rho[i] = ps.rho0[i] = kSandDensity;
    ps.phase[i] = static_cast<std::uint8_t>(Phase::Sand);
  }
  PorousParams q = p;
  q.initial_saturation = S0;
  init_porous(ps, q);
  return ps;
}

/// Σ m v over all particles and Σ m |v| (the scale of its round-off).
std::pair<Vec<2>, double> momentum(const ParticleSet<2>& ps) {
  Vec<2> P = Vec<2>::Zero();
  double scale = 0.0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    P += ps.m[i] * ps.v[i];
    scale += ps.m[i] * ps.v[i].norm();
  }
  return {P, scale};
}

SimulationParams sand_sim_params(const PorousParams& p) {
  SimulationParams sp;
  sp.dt_max = 2.5e-4;
  sp.eos.sound_speed = 15.0;
  sp.gravity = {0.0, -9.81};
  sp.domain_min = {-1.0, -1.0};
  sp.domain_max = {1.0, 1.0};
  sp.porous = p;
  return sp;
}

}  // namespace

BOOST_AUTO_TEST_CASE(a_saturated_grain_falls_with_the_weight_of_grain_and_water) {
  // Thesis §3.4 ("the absorbed fluid mass should be taken into account to all computations"),
  // Lenaerts 2008 ("particles gain weight"): a lone saturated sand grain (φ = 0.4, its pores
  // holding m_p = φ ρ^f V, no flow: k = 0) falling for 40 steps is pulled by the weight of grain
  // and water, (m_dry + m_p) g, so its momentum after t is (m_dry + m_p) g t (to 1e-12) and its
  // mass is m_dry + m_p: 1.25 m_dry here.
  PorousParams p = test_params();
  p.permeability = 0.0;
  ParticleSet<2> ps = wet_sand(p, {0.0, 0.0}, {kDx, kDx}, 1.0);
  const double dry = lattice_mass<2>(kSandDensity, kDx, 2.0 * kDx, kernel::DensityKernel::Spiky);
  const double water = p.fluid_density * p.porosity * dry / kSandDensity;
  Simulator<2> sim(std::move(ps), sand_sim_params(p));
  double t = 0.0;
  for (int step = 0; step < 40; ++step) t += sim.step();
  const auto& q = sim.particles();
  BOOST_TEST_REQUIRE(q.size() == 1u);
  BOOST_TEST(q.m[0] == dry + water, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(q.m[0] * q.v[0][1] == -(dry + water) * 9.81 * t, boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(absorption_and_emission_conserve_the_momentum_of_water_and_sand) {
  // Moving porous sand (S = 0.95, drained downwards by gravity in Darcy's law, no suction) under
  // a water blob, every particle with its own velocity; only porous_step acts (no forces), for
  // 600 steps. Water the sand absorbs brings its momentum Δm v_water, water it emits (into new
  // particles below, or into the blob) takes Δm v_sand, absorbed water passed between grains
  // carries the giver's velocity: Σ m v over water and sand is constant to 1e-12 of Σ m |v|,
  // while water particles are absorbed whole and new ones are emitted.
  PorousParams p = test_params();
  p.capillary_constant = 0.0;
  ParticleSet<2> ps = wet_sand(p, {0.0, 0.10}, {0.1, 0.16}, 0.95);
  add_block(ps, p, Phase::Water, {0.03, 0.16}, {0.07, 0.20}, 0.0);
  for (std::size_t i = 0; i < ps.size(); ++i)
    ps.v[i] = ps.phase_of(i) == Phase::Water ? Vec<2>(-0.4, -0.8) : Vec<2>(0.2 + 3.0 * (ps.x[i][1] - 0.1), -0.1 + ps.x[i][0]);
  const auto [P0, scale] = momentum(ps);
  const Vec<2> g(0.0, -9.81);
  NeighbourGrid<2> nb;
  PorousWork<2> work;
  PorousStepCounts total;
  double worst = 0.0;
  for (int step = 0; step < 600; ++step) {
    nb.rebuild(ps);
    compute_density(ps, nb, p.density_kernel, kRho);
    const PorousStepCounts c = porous_step(ps, nb, p, g, 2.5e-4, work);
    ps.compact();
    total.absorbed += c.absorbed;
    total.created += c.created;
    worst = std::max(worst, (momentum(ps).first - P0).norm() / scale);
  }
  BOOST_TEST(total.absorbed > 0u);
  BOOST_TEST(total.created > 0u);
  BOOST_TEST(worst <= 1e-12);
}

BOOST_AUTO_TEST_CASE(a_resting_saturated_bed_has_the_wet_density_of_eq_31) {
  // [thesis eq. 31]: a saturated sand bed (dry ρ0 = 1600, φ = 0.4, no flow) resting in a box
  // for 400 steps: every grain's rest density is ρ0 + φ ρ^f = 2000 (to 1e-12) and the summation
  // density (eq 6) of the grains away from the surface and the floor is within 1 % of it.
  PorousParams p = test_params();
  p.permeability = 0.0;
  ParticleSet<2> ps = wet_sand(p, {0.0, 0.0}, {0.12, 0.08}, 1.0);
  add_block(ps, p, Phase::Boundary, {-0.03, -0.03}, {0.15, 0.0}, 0.0);  // floor
  add_block(ps, p, Phase::Boundary, {-0.03, 0.0}, {0.0, 0.1}, 0.0);     // side walls
  add_block(ps, p, Phase::Boundary, {0.12, 0.0}, {0.15, 0.1}, 0.0);
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (ps.phase_of(i) == Phase::Boundary) ps.porosity[i] = ps.absorbed[i] = 0.0;
  Simulator<2> sim(std::move(ps), sand_sim_params(p));
  for (int step = 0; step < 400; ++step) sim.step();
  const auto& q = sim.particles();
  const double wet = kSandDensity + p.porosity * p.fluid_density;
  std::size_t inner = 0;
  for (std::size_t i = 0; i < q.size(); ++i) {
    if (q.phase_of(i) != Phase::Sand) continue;
    BOOST_TEST(q.rho0[i] == wet, boost::test_tools::tolerance(1e-12));
    if (q.x[i][0] < 0.03 || q.x[i][0] > 0.09 || q.x[i][1] < 0.02 || q.x[i][1] > 0.05) continue;
    BOOST_TEST(q.rho[i] == wet, boost::test_tools::tolerance(0.01));
    ++inner;
  }
  BOOST_TEST(inner > 0u);
}

BOOST_AUTO_TEST_CASE(effective_pressure_eq_32_weakens_wet_sand) {
  // [thesis eq. 32] as Terzaghi's effective pressure p' = max(0, p − η k^p S): monotonically lower
  // with S (so the friction and yield threshold sin φ p' of eqs 8 and 10 drop), never negative.
  double prev = INFINITY;
  for (int k = 0; k <= 10; ++k) {
    const double pe = effective_pressure(3000.0, 1.0, 2000.0, k / 10.0);
    BOOST_TEST(pe < prev);
    BOOST_TEST(pe >= 0.0);
    prev = pe;
  }
  BOOST_TEST(effective_pressure(1000.0, 1.0, 2000.0, 1.0) == 0.0);
}

BOOST_AUTO_TEST_CASE(wet_sand_friction_uses_the_effective_pressure_eq_32) {
  // [thesis eq. 32] fed into the sand: in simple shear the frictional stress of eq 8 is
  // proportional to the pressure, so at S = 1/2 with η k^p = 3000 Pa and p = 4000 Pa it is p'/p = 5/8 of the dry one,
  // and dry sand (S = 0) is unchanged by η k^p.
  ParticleSet<2> ps = test::square_lattice(12, kDx, 2.0, 2650.0, Phase::Sand);
  NeighbourGrid<2> nb;
  shear_sand(ps, nb, 2.0);
  SandParams sand;
  sand.rigid_clusters = false;
  MatArray<2> dry, dry_kp, wet;
  VecArrayOf<2> predicted;
  update_sand_state(ps, nb, sand, 9.81, 1e-4, dry, predicted);
  update_sand_state(ps, nb, sand, 9.81, 1e-4, dry_kp, predicted, 1.0, 3000.0);
  ps.add_porous_fields();
  for (auto& S : ps.saturation) S = 0.5;
  update_sand_state(ps, nb, sand, 9.81, 1e-4, wet, predicted, 1.0, 3000.0);
  BOOST_TEST(dry[kCentre].norm() > 0.0);
  BOOST_TEST((dry_kp[kCentre] - dry[kCentre]).norm() == 0.0);
  BOOST_TEST(wet[kCentre].norm() / dry[kCentre].norm() == (4000.0 - 0.5 * 3000.0) / 4000.0, boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(water_balance_over_1000_steps_with_absorption_and_emission) {
  // [thesis eq. 28] - [thesis eq. 30] with absorption (water particles shrink and are deleted)
  // and emission (new water particles below the bed): free + absorbed water constant to 1e-12,
  // and 0 <= S <= 1 at every porous particle and step.
  Simulator<2> sim = exchange_scene();
  const double initial = total_water(sim.particles());
  const std::int64_t first_id = sim.particles().next_id();
  const std::size_t water0 = 16;
  double worst = 0.0, s_min = 1.0, s_max = 0.0;
  for (int step = 0; step < 1000; ++step) {
    sim.step();
    const auto& ps = sim.particles();
    worst = std::max(worst, std::abs(total_water(ps) - initial) / initial);
    for (std::size_t i = 0; i < ps.size(); ++i)
      if (ps.porosity[i] > 0.0) {
        const double S = ps.absorbed[i] / (kRho * ps.porosity[i] * porous_volume(ps, i));
        s_min = std::min(s_min, S);
        s_max = std::max(s_max, S);
      }
  }
  const auto& ps = sim.particles();
  std::size_t original = 0;
  for (std::size_t i = 0; i < ps.size(); ++i) original += ps.phase_of(i) == Phase::Water && ps.id[i] < first_id;
  BOOST_TEST(worst <= 1e-12);
  BOOST_TEST(s_min >= -1e-12);
  BOOST_TEST(s_max <= 1.0 + 1e-12);
  BOOST_TEST(original < water0);                        // some of the blob was absorbed and deleted
  BOOST_TEST(ps.next_id() > first_id);                  // emission created water particles
}

BOOST_AUTO_TEST_CASE(a_large_emission_store_leaves_in_particles_of_at_most_a_full_mass) {
  // Every porous particle of the bed's bottom row (saturated, exposed to the air below) starts
  // with 3.5 full water masses waiting in its emission store. Over 400 steps the stores leave as
  // new water particles of at most one full mass each (never one particle of 3.5 masses, which
  // would be 3.5x as dense as water), the total water stays constant to 1e-12, and the stores
  // drain: less than half of what they held is left.
  const Simulator<2> start = exchange_scene();
  const PorousParams p = test_params();
  ParticleSet<2> ps = start.particles();
  std::size_t bottom = 0;
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (ps.porosity[i] > 0.0 && ps.x[i][1] < 0.11) {
      ps.emit_store[i] = 3.5 * p.water_mass;
      ++bottom;
    }
  BOOST_TEST_REQUIRE(bottom == 10u);
  Simulator<2> sim(std::move(ps), start.params());
  const double initial = total_water(sim.particles());
  const std::int64_t first_id = sim.particles().next_id();
  double heaviest = 0.0, worst = 0.0;
  for (int step = 0; step < 400; ++step) {
    sim.step();
    const auto& q = sim.particles();
    worst = std::max(worst, std::abs(total_water(q) - initial) / initial);
    for (std::size_t i = 0; i < q.size(); ++i)
      if (q.phase_of(i) == Phase::Water && q.id[i] >= first_id) heaviest = std::max(heaviest, q.m[i]);
  }
  double stored = 0.0;
  const auto& q = sim.particles();
  for (std::size_t i = 0; i < q.size(); ++i) stored += q.emit_store[i];
  BOOST_TEST(heaviest > 0.0);
  BOOST_TEST(heaviest <= p.water_mass * (1.0 + 1e-12));
  BOOST_TEST(worst <= 1e-12);
  BOOST_TEST(stored < 0.5 * 3.5 * bottom * p.water_mass);
}

BOOST_AUTO_TEST_CASE(results_do_not_depend_on_the_thread_count) {
  // Gather loops, pair flows computed identically by both particles, serial queues: 1 and 2
  // threads give the same bits.
  std::string sums[2];
  double water[2];
  for (int t = 1; t <= 2; ++t) {
    omp_set_num_threads(t);
    Simulator<2> sim = exchange_scene();
    for (int step = 0; step < 300; ++step) sim.step();
    sums[t - 1] = sim.particles().checksum();
    water[t - 1] = total_water(sim.particles());
  }
  BOOST_TEST(sums[0] == sums[1]);
  BOOST_TEST(water[0] == water[1]);
}

BOOST_AUTO_TEST_CASE(green_ampt_worked_values) {
  // docs/references.md §4: K = 1e-4 m/s, ψ = 0.10 m, Δθ = 0.3.
  const double t[] = {10.0, 60.0, 300.0, 1800.0};
  const double F[] = {8.426e-3, 23.167e-3, 64.386e-3, 246.646e-3};
  for (int k = 0; k < 4; ++k)
    BOOST_TEST(analytic::green_ampt_infiltration(1e-4, 0.1, 0.3, t[k]) == F[k], boost::test_tools::tolerance(1e-4));
  const double Fk = analytic::green_ampt_infiltration(1e-4, 0.1, 0.3, 300.0);
  BOOST_TEST(1e-4 * 300.0 == Fk - 0.03 * std::log(1.0 + Fk / 0.03), boost::test_tools::tolerance(1e-10));
}

BOOST_AUTO_TEST_CASE(capillary_drive_and_fringe_references) {
  // ψ = α H_c B(α, β + 2) equals ∫ k_r dh by quadrature; the fringe S(z) holds φ k^c/(ρ g (α+1)).
  const double Hc = 0.2, alpha = 0.1, beta = 3.0;
  double psi = 0.0;
  const int n = 200000;
  for (int k = 0; k < n; ++k) {
    const double h = (k + 0.5) / n * Hc;
    psi += std::pow(1.0 - std::pow(h / Hc, 1.0 / alpha), beta + 1.0) * Hc / n;
  }
  BOOST_TEST(analytic::capillary_drive(Hc, alpha, beta) == psi, boost::test_tools::tolerance(1e-6));
  const double kc = Hc * kRho * 9.81;
  double held = 0.0;
  for (int k = 0; k < n; ++k) held += 0.4 * analytic::equilibrium_saturation((k + 0.5) / n * Hc, kc, kRho, 9.81, alpha) * Hc / n;
  BOOST_TEST(analytic::held_water(kc, kRho, 9.81, alpha, 0.4) == held, boost::test_tools::tolerance(1e-6));
}


BOOST_AUTO_TEST_CASE(wet_cohesion_falls_linearly_to_zero_at_saturation) {
  // Our cohesion-saturation law (solver/porous/wet_cohesion.hpp, Tampubolon et al. 2017): c0 (1 - S),
  // full when dry, gone when saturated, monotone, S clamped to [0, 1].
  BOOST_TEST(wet_cohesion(2000.0, 0.0) == 2000.0);
  BOOST_TEST(wet_cohesion(2000.0, 1.0) == 0.0);
  BOOST_TEST(wet_cohesion(2000.0, 0.25) == 1500.0, boost::test_tools::tolerance(1e-14));
  BOOST_TEST(wet_cohesion(2000.0, 1.5) == 0.0);
  BOOST_TEST(wet_cohesion(2000.0, -0.5) == 2000.0);
  for (double S = 0.0; S < 1.0; S += 0.1) BOOST_TEST(wet_cohesion(2000.0, S + 0.1) < wet_cohesion(2000.0, S));
}

BOOST_AUTO_TEST_CASE(saturated_sand_loses_the_cohesion_that_held_it_rigid) {
  // Eq 10 with the wet cohesion: a sheared lattice that only cohesion keeps rigid (it yields with
  // c = 0) stays rigid while dry, yields when saturated, and stays rigid at S = 1 when the
  // cohesion loss is switched off (eq 32 is off here: k^p = 0).
  ParticleSet<2> ps = test::square_lattice(12, kDx, 2.0, 2650.0, Phase::Sand);
  NeighbourGrid<2> nb;
  shear_sand(ps, nb, 20.0);
  SandParams sand;
  sand.rigid_clusters = false;
  MatArray<2> stress;
  VecArrayOf<2> predicted;
  update_sand_state(ps, nb, sand, 9.81, 1e-4, stress, predicted);
  BOOST_TEST(ps.rigid[kCentre] == 0);  // cohesionless: yields
  sand.cohesion = 1e6;
  update_sand_state(ps, nb, sand, 9.81, 1e-4, stress, predicted);
  BOOST_TEST(ps.rigid[kCentre] == 1);  // dry and cohesive: rigid
  ps.add_porous_fields();
  for (auto& S : ps.saturation) S = 1.0;
  update_sand_state(ps, nb, sand, 9.81, 1e-4, stress, predicted);
  BOOST_TEST(ps.rigid[kCentre] == 0);  // saturated: the cohesion is gone
  sand.wet_cohesion_loss = false;
  update_sand_state(ps, nb, sand, 9.81, 1e-4, stress, predicted);
  BOOST_TEST(ps.rigid[kCentre] == 1);
}

BOOST_AUTO_TEST_CASE(compressed_wet_sand_squeezes_out_pore_water_and_keeps_the_balance) {
  // Moving porous sand, saturated, settles on a floor: its density rises, its pore volume
  // (eq 24) falls, and the water that no longer fits goes to the emission store
  // (porous_flow.cpp squeeze_out). The raw saturation m_p/(rho^f phi V) of every sand particle
  // stays <= 1 after every step, some water is squeezed out, and free + stored + absorbed water is
  // constant to 1e-12.
  const PorousParams p = test_params();
  ParticleSet<2> ps;
  add_block(ps, p, Phase::Sand, {0.0, 0.0}, {0.1, 0.1}, 1.0);
  add_block(ps, p, Phase::Boundary, {-0.1, -0.03}, {0.2, 0.0}, 0.0);
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (ps.x[i][1] < 0.0) ps.porosity[i] = ps.absorbed[i] = 0.0;
  Simulator<2> sim(std::move(ps), sand_sim_params(p));
  const double initial = total_water(sim.particles());
  double worst = 0.0, s_max = 0.0, stored = 0.0;
  for (int step = 0; step < 200; ++step) {
    sim.step();
    const auto& q = sim.particles();
    worst = std::max(worst, std::abs(total_water(q) - initial) / initial);
    for (std::size_t i = 0; i < q.size(); ++i) {
      if (q.phase_of(i) != Phase::Sand) continue;
      s_max = std::max(s_max, q.absorbed[i] / (kRho * q.porosity[i] * porous_volume(q, i)));
      stored = std::max(stored, q.emit_store[i]);
    }
  }
  BOOST_TEST(stored > 0.0);
  BOOST_TEST(s_max <= 1.0 + 1e-12);
  BOOST_TEST(worst <= 1e-12);
}
BOOST_AUTO_TEST_CASE(partial_water_takes_the_pressure_of_the_water_around_it) {
  // A partial particle (10 % of m0) at the centre of a full water lattice whose pressure is linear,
  // p = 2000 + 5e4 x: it takes the Shepard average of its full neighbours, which on the symmetric
  // lattice is exactly p at its position, whatever its own state equation said (1 MPa here). Full
  // particles keep their pressure, and so does a partial particle with only sand around it.
  const PorousParams p = test_params();
  ParticleSet<2> ps;
  add_block(ps, p, Phase::Water, {0.0, 0.0}, {0.13, 0.13}, 0.0);
  const auto centre = static_cast<std::size_t>(6 * 13 + 6);  // the middle of the 13 x 13 block
  const double expected = 2000.0 + 5e4 * ps.x[centre][0];
  for (std::size_t i = 0; i < ps.size(); ++i) ps.p[i] = 2000.0 + 5e4 * ps.x[i][0];
  ps.m[centre] = 0.1 * p.water_mass;
  ps.p[centre] = 1e6;
  const std::size_t lone = ps.append();  // partial water among sand, far from the water
  ps.x[lone] = {0.5, 0.5};
  ps.m[lone] = 0.3 * p.water_mass;
  ps.h[lone] = p.water_support;
  ps.rho[lone] = ps.rho0[lone] = kRho;
  ps.p[lone] = 3e5;
  for (const Vec<2>& dx : {Vec<2>(kDx, 0.0), Vec<2>(-kDx, 0.0), Vec<2>(0.0, kDx), Vec<2>(0.0, -kDx)}) {
    const std::size_t k = ps.append();
    ps.x[k] = ps.x[lone] + dx;
    ps.m[k] = 2.0 * p.water_mass;
    ps.h[k] = p.water_support;
    ps.rho[k] = ps.rho0[k] = 2.0 * kRho;
    ps.p[k] = 5000.0;
    ps.phase[k] = static_cast<std::uint8_t>(Phase::Sand);
  }
  const std::vector<double> before = ps.p;
  NeighbourGrid<2> nb;
  nb.rebuild(ps);
  set_partial_water_pressure(ps, nb, p.water_mass);
  BOOST_TEST(ps.p[centre] == expected, boost::test_tools::tolerance(1e-12));
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (i != centre) BOOST_TEST(ps.p[i] == before[i]);
}

BOOST_AUTO_TEST_CASE(a_parcel_inside_a_fixed_bed_takes_the_pore_pressure_around_it) {
  // A parcel (30 % of m0) that drifted into a saturated fixed bed, with no full water particle in
  // its support, sits among bed particles closer than the lattice spacing: its own state equation
  // (rest density of its mass) reads a compression of tens of percent and a pressure of hundreds of
  // kPa, which threw it and the pond above it out of darcy_column. It takes instead the pore-water
  // pressure of the bed around it, the Shepard average of the bed's P^p, here linear
  // (P^p = 800 + 3e4 y) on a lattice symmetric about the parcel, so exactly P^p at its place.
  const PorousParams p = test_params();
  ParticleSet<2> ps;
  add_block(ps, p, Phase::Boundary, {0.0, 0.0}, {0.13, 0.13}, 1.0);
  for (std::size_t i = 0; i < ps.size(); ++i) ps.pore_pressure[i] = 800.0 + 3e4 * ps.x[i][1];
  const auto centre = static_cast<std::size_t>(6 * 13 + 6);
  const std::size_t parcel = ps.append();
  ps.x[parcel] = ps.x[centre];
  ps.m[parcel] = 0.3 * p.water_mass;
  ps.h[parcel] = p.water_support;
  const double w0 = kernel::density_kernel<2>(p.density_kernel, 0.0, p.water_support);
  ps.rho0[parcel] = partial_water_rest_density(kRho, p.water_mass, ps.m[parcel], w0);
  NeighbourGrid<2> nb;
  nb.rebuild(ps);
  compute_density(ps, nb, p.density_kernel, kRho);
  EquationOfState eos;
  eos.sound_speed = 15.0;
  ps.p[parcel] = eos.pressure(ps.rho[parcel], ps.rho0[parcel]);
  BOOST_TEST_MESSAGE("parcel's own pressure in the bed: " << ps.p[parcel] << " Pa");
  BOOST_TEST(ps.p[parcel] > 1e5);
  set_partial_water_pressure(ps, nb, p.water_mass);
  BOOST_TEST(ps.p[parcel] == 800.0 + 3e4 * ps.x[parcel][1], boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(a_compressed_water_particle_takes_no_water_from_the_bed) {
  // The parcel of BedFace, 30 % of m0, in the face of a saturated bed under the pond's pressure:
  // inside the face its summation density is more than 10 % above its rest density (the bed's
  // particles are closer than the spacing), and water it took from the bed there would go into a place already
  // overfull, raising its own state equation's pressure as it refills (darcy_column threw such
  // parcels out of the face at metres per second). It takes none; the same parcel at its own
  // lattice site in the pond, not compressed, does take water from the bed.
  const Vec<2> g(0.0, -9.81);
  double gained[2];
  for (const bool inside : {true, false}) {
    BedFace scene;
    if (!inside) scene.ps.x[scene.parcel][0] = 0.055;
    scene.nb.rebuild(scene.ps);
    ParticleSet<2>& ps = scene.ps;
    const double w0 = kernel::density_kernel<2>(scene.p.density_kernel, 0.0, scene.p.water_support);
    ps.m[scene.parcel] = 0.3 * scene.p.water_mass;
    ps.rho0[scene.parcel] = partial_water_rest_density(kRho, scene.p.water_mass, ps.m[scene.parcel], w0);
    compute_density(ps, scene.nb, scene.p.density_kernel, kRho);
    BOOST_TEST((ps.rho[scene.parcel] > 1.1 * ps.rho0[scene.parcel]) == inside);
    const double before = ps.m[scene.parcel];
    PorousWork<2> w;
    porous_step(ps, scene.nb, scene.p, g, 1e-4, w);
    gained[inside ? 0 : 1] = ps.m[scene.parcel] - before;
  }
  BOOST_TEST_MESSAGE("parcel's gain in one step: inside the face " << gained[0] << " kg, at its site " << gained[1] << " kg");
  BOOST_TEST(gained[0] <= 0.0);
  BOOST_TEST(gained[1] > 0.0);
}

BOOST_AUTO_TEST_CASE(partial_water_accelerates_like_a_full_particle_at_its_place) {
  // A parcel of 3 % of m0 (rest density ρ^f − (m0 − m) W(0, h), as porous_flow gives it) at the
  // centre of a full water lattice whose pressure is linear, p = 2000 + 5e4 x. Its own summation
  // density is far below ρ^f, so with it its volume m/ρ would be several times its share of the
  // water and so would its pressure acceleration. With the density of a full particle at its place
  // (set_partial_water_density) it has that particle's density (exactly, up to round-off) and its
  // acceleration agrees within 10 % (its neighbours' densities still miss the parcel's absent
  // mass, so their volumes are larger).
  const PorousParams p = test_params();
  ParticleSet<2> ps;
  add_block(ps, p, Phase::Water, {0.0, 0.0}, {0.13, 0.13}, 0.0);
  const auto centre = static_cast<std::size_t>(6 * 13 + 6);  // the middle of the 13 x 13 block
  NeighbourGrid<2> nb;
  nb.rebuild(ps);
  const auto acceleration_at_centre = [&](double mass) {
    ps.m[centre] = mass;
    ps.rho0[centre] = kRho - (p.water_mass - mass) * kernel::density_kernel<2>(p.density_kernel, 0.0, p.water_support);
    compute_density(ps, nb, p.density_kernel, kRho);
    for (std::size_t i = 0; i < ps.size(); ++i) {
      ps.p[i] = 2000.0 + 5e4 * ps.x[i][0];
      ps.force[i].setZero();
    }
    set_partial_water_pressure(ps, nb, p.water_mass);
    set_partial_water_density(ps, p.water_mass, kRho);
    WaterParams water;
    water.gradient_correction = false;
    add_water_forces(ps, nb, water, {});
    return std::pair{ps.rho[centre], Vec<2>(ps.force[centre] / mass)};
  };
  const auto [rho_full, a_full] = acceleration_at_centre(p.water_mass);
  const auto [rho_parcel, a_parcel] = acceleration_at_centre(0.03 * p.water_mass);
  BOOST_TEST(rho_parcel == rho_full, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(a_full[0] < 0.0);  // pushed down the pressure gradient
  BOOST_TEST((a_parcel - a_full).norm() <= 0.1 * a_full.norm());
}

BOOST_AUTO_TEST_CASE(a_parcel_filled_back_inside_the_bed_face_regains_its_pressure_gradually) {
  // How capillary_rise blew up at 0.005 m, in a small scene (BedFace): the bed fills the parcel
  // that drifted into its face back across kPartialWaterFraction of a full particle. At its place its own state equation
  // (eq 7 with the rest density of its mass) reads far more than the pond's pressure; with a switch
  // at the threshold it took that pressure in the step of filling that crossed it, and its
  // acceleration jumped by thousands of m/s² (parcels were thrown out of the pools at metres per
  // second). Its pressure and acceleration must be continuous in its mass: across the threshold
  // (±1e-6 of a full mass, a fraction of one step's filling) they change by less than 1 %, and
  // they rise towards its own state equation only as it fills (own_pressure_weight).
  BedFace scene;
  const State below = scene.state_at(kPartialWaterFraction - 1e-6), above = scene.state_at(kPartialWaterFraction + 1e-6);
  const State three_quarters = scene.state_at(0.75), full = scene.state_at(1.0);
  BOOST_TEST_MESSAGE("own pressure at the threshold " << above.own << " Pa; taken " << below.p << " / " << above.p
                     << " Pa; acceleration " << below.a.norm() << " / " << above.a.norm() << " m/s^2; at 3/4 "
                     << three_quarters.p << " Pa, full " << full.p << " Pa");
  BOOST_TEST(above.own > 20.0 * 1000.0);  // the compression the parcel's place holds
  BOOST_TEST(below.p == 1000.0, boost::test_tools::tolerance(1e-12));  // a parcel: the pond's pressure
  BOOST_TEST(std::abs(above.p - below.p) <= 0.01 * below.p);
  BOOST_TEST((above.a - below.a).norm() <= 0.01 * below.a.norm());
  BOOST_TEST(three_quarters.p > above.p);  // it regains its own pressure as it fills
  BOOST_TEST(three_quarters.p < full.p);
  BOOST_TEST(full.p == full.own);  // a full particle keeps its state equation, bitwise
}

BOOST_AUTO_TEST_CASE(a_parcel_at_a_bed_face_takes_the_uncorrected_kernel) {
  // The parcel of BedFace (30 % of a full mass) in the pond's uniform pressure: the true pressure
  // force is zero, and what the kernel gives it is the push of its incomplete neighbourhood
  // (2 P_i Σ_j V_j ∇W_ij), out of the bed's face, which only a particle's own state equation holds
  // in check. The kernel-gradient correction must not amplify that push on a particle without its
  // own pressure: with the parcels' corrections weighted by their own-pressure weight
  // (weight_partial_water_corrections) the parcel is pushed no harder than by the uncorrected
  // kernel; with the correction at full weight it was pushed harder (parcels thrown out of
  // capillary_rise's pools at 0.005 m). A full particle at the same place keeps its full
  // correction, bitwise.
  BedFace scene;
  using C = BedFace::Correction;
  const State plain = scene.state_at(0.3, C::None), weighted = scene.state_at(0.3, C::Weighted);
  const State unweighted = scene.state_at(0.3, C::Unweighted);
  BOOST_TEST_MESSAGE("parcel acceleration: uncorrected " << plain.a.transpose() << ", weighted " << weighted.a.transpose()
                     << ", unweighted " << unweighted.a.transpose() << " m/s^2");
  BOOST_TEST(plain.a[0] > 0.0);  // out of the bed's face
  BOOST_TEST(weighted.a.norm() <= plain.a.norm());
  BOOST_TEST(unweighted.a.norm() > plain.a.norm());
  const State full = scene.state_at(1.0, C::Weighted), full_unweighted = scene.state_at(1.0, C::Unweighted);
  BOOST_TEST((full.a - full_unweighted.a).norm() == 0.0);
}

BOOST_AUTO_TEST_SUITE_END()
