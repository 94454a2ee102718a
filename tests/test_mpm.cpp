// Two-grid MPM after Tampubolon et al. 2017 (solver/mpm/): each test pins one formula of the method
// (the nodal exchange, the Hencky stress, the return mapping and its volume correction, the MLS
// force through a column at rest, the rest state of a cohesive block, the wet cut against Rankine's
// height) or its determinism.
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <omp.h>
#include <optional>

#include "core/checksum.hpp"
#include "core/errors.hpp"
#include "mpm/exchange.hpp"
#include "mpm/mpm_method.hpp"
#include "mpm/mpm_solver.hpp"
#include "mpm/svd.hpp"
#include "reference/analytic/rankine.hpp"
#include "reference/analytic/terzaghi.hpp"
#include "support/long_run.hpp"

using namespace sc;
using namespace sc::mpm;

namespace {

/// A box [0, size] with smooth (frictionless) sides on a grid of cell width h, no gravity, sand
/// with E = 1e6 Pa, ν = 0.3, φ = 30 deg, ρ = 1800 kg/m^3 and water as in the suite's cases.
template <int D>
Params<D> box(const Vec<D>& size, double h) {
  Params<D> p;
  p.grid.h = h;
  p.grid.origin = Vec<D>::Constant(-2.0 * h);
  for (int d = 0; d < D; ++d) p.grid.count[d] = std::lround(size[d] / h) + 5;
  p.wall_lo = Vec<D>::Zero();
  p.wall_hi = size;
  p.sand = SandModel::from(D, 1e6, 0.3, 30.0, true);
  p.sand_density = 1800.0;
  p.eos.sound_speed = 20.0;
  return p;
}
Params<2> box(double w, double ht, double h) { return box<2>(Vec<2>(w, ht), h); }

/// Particles on the lattice of spacing dx over [lo, hi], each ρ dx^D of phase `ph`.
template <int D>
void fill(Particles<D>& ps, const Vec<D>& lo, const Vec<D>& hi, double dx, double rho, Phase ph) {
  std::array<long, D> n{};
  long count = 1;
  for (int d = 0; d < D; ++d) count *= (n[d] = std::lround((hi - lo)[d] / dx));
  for (long k = 0; k < count; ++k) {
    Vec<D> x;
    long rest = k;
    for (int d = 0; d < D; ++d) {
      x[d] = lo[d] + dx * (static_cast<double>(rest % n[d]) + 0.5);
      rest /= n[d];
    }
    ps.add(x, rho * std::pow(dx, D), std::pow(dx, D), ph);
  }
}

/// Water in the pores of sand on the lattice of spacing dx over [lo, hi]: a particle on each site,
/// ρ_w n dx^D, volume n dx^D, in pores of porosity n.
template <int D>
void fill_pores(Particles<D>& ps, const Vec<D>& lo, const Vec<D>& hi, double dx, double n) {
  const std::size_t first = ps.size();
  fill<D>(ps, lo, hi, dx, 1000.0, Phase::Water);
  for (std::size_t i = first; i < ps.size(); ++i) {
    ps.m[i] *= n;
    ps.V0[i] *= n;
    ps.porosity[i] = n;
  }
}

/// The relative error of the mean vertical stress of the bottom particle layer of an elastic sand
/// column of height H (ρ = 1800 kg/m^3, ν = 0, a cohesion it never reaches) in a smooth box of
/// footprint `width`, damped to rest under gravity on a grid of cell h (2 particles per cell
/// along each axis), against −ρ g H. `saturated`: water fills its pores (n = 0.4, water particles of
/// n dx^D on the sand's sites, K = 1e-3 m/s), and the effective stress is compared with the buoyant
/// weight −(ρ − (1 − n) ρ_w) g H.
template <int D>
double column_stress_error(double width, double H, double h, bool saturated = false) {
  const double dx = h / 2.0;
  Vec<D> size = Vec<D>::Constant(width), top = Vec<D>::Constant(width);
  size[D - 1] = 2.0 * H;
  top[D - 1] = H;
  Params<D> p = box<D>(size, h);
  p.sand = SandModel::from(D, 1e6, 0.0, 30.0, true);
  p.cohesion = 1e7;
  p.gravity[D - 1] = -9.81;
  p.relax_until = 1e9;
  p.relax_rate = 40.0;
  Particles<D> ps;
  fill<D>(ps, Vec<D>::Zero(), top, dx, 1800.0, Phase::Sand);
  const double n = p.porosity, weight = saturated ? 1800.0 - (1.0 - n) * 1000.0 : 1800.0;
  if (saturated) {
    p.wet_cohesion_loss = false;
    p.cfl = 0.2;  // the pore water stiffens the moving skeleton, explicitly through its porosity
    p.drag = drag_per_volume(n, 1000.0, 9.81, 1e-3);
    fill_pores<D>(ps, Vec<D>::Zero(), top, dx, n);
  }
  MpmSolver<D> solver(p, ps);
  while (solver.time() < 0.6) solver.advance(1e-3);
  double sum = 0.0;
  int count = 0;
  for (std::size_t i = 0; i < solver.particles().size(); ++i)
    if (solver.particles().is_sand(i) && solver.particles().x[i][D - 1] < dx) {
      sum += solver.kirchhoff(i)(D - 1, D - 1) / solver.particles().J[i];
      ++count;
    }
  const double exact = -weight * 9.81 * H;
  return std::abs(sum / count - exact) / std::abs(exact);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(mpm)

// [Tampubolon 2017: eq. 22] One node, no other force: the implicit exchange keeps the total
// momentum to round-off and shrinks the relative velocity by exactly 1/(1 + Δt ξ (1/m_s + 1/m_w))
// per step (to 1e-12 of the velocities, the round-off of their difference), for drags from weak to
// far stiffer than the step (an explicit exchange would overshoot and flip the sign of the
// relative velocity for Δt ξ (1/m_s + 1/m_w) > 2).
BOOST_AUTO_TEST_CASE(the_exchange_on_one_node_keeps_momentum_and_decays_the_relative_velocity_exactly) {
  const double m_s = 2.0, m_w = 0.5;
  for (const double a : {0.01, 0.1, 1.0, 10.0, 100.0}) {
    Vec<2> v_s(0.3, -1.0), v_w(-0.7, 2.0);
    const Vec<2> p0 = m_s * v_s + m_w * v_w;
    const double factor = 1.0 / (1.0 + a * (1.0 / m_s + 1.0 / m_w));
    for (int step = 0; step < 20; ++step) {
      const Vec<2> u = v_w - v_s;
      exchange_momentum<2>(m_s, m_w, a, v_s, v_w);
      BOOST_TEST(((m_s * v_s + m_w * v_w) - p0).norm() <= 1e-12 * p0.norm());
      BOOST_TEST(((v_w - v_s) - factor * u).norm() <= 1e-12 * (v_s.norm() + v_w.norm()));
    }
  }
}

// [Tampubolon 2017: drag c_E, nodal drag ξ] Where the water fills the pores, the drag of a node is
// c_E V^s with c_E = n² ρ_w g / K, the coefficient of Darcy's law: a seepage at the Darcy flux
// q = K i needs the driving force n ρ_w g i per unit volume, which is c_E (v_w − v_s) with
// v_w − v_s = q / n. On a node across a bed's surface (porosity n_i, half of it bed) the water
// moves at q / n_i, and the drag is still that of the bed's share at the pore velocity, c_E φ q / n.
// [Zienkiewicz & Shiomi 1984: volume fractions] The node's porosity is n in the bed, 1 in open
// water, 1 − (1 − n)/2 where the bed fills half of what the water fills, and 1 − (1 − n)/J in a
// skeleton compressed to J.
BOOST_AUTO_TEST_CASE(the_drag_coefficient_gives_darcys_flux_in_a_steady_seepage) {
  const double n = 0.4, rho = 1000.0, g = 9.81, K = 1e-3, i = 0.5;
  const double cE = drag_per_volume(n, rho, g, K);
  BOOST_TEST(cE == 1.5696e6, boost::test_tools::tolerance(1e-12));
  const double q = K * i;
  BOOST_TEST(cE * q / n == n * rho * g * i, boost::test_tools::tolerance(1e-12));
  // Saturation is the water's share of the pore volume, and the drag acts in that share only.
  BOOST_TEST(node_saturation(2.0, 0.4, n) == 0.5, boost::test_tools::tolerance(1e-15));
  BOOST_TEST(node_saturation(2.0, 5.0, n) == 1.0);
  BOOST_TEST(node_saturation(0.0, 5.0, n) == 0.0);
  BOOST_TEST(node_drag(cE, 2.0, 0.5, n, n) == cE, boost::test_tools::tolerance(1e-15));
  const double half = node_porosity(0.5, 0.5, 1.0, n);
  BOOST_TEST(half == 1.0 - 0.5 * (1.0 - n), boost::test_tools::tolerance(1e-15));
  BOOST_TEST(node_porosity(1.0, 1.0, 1.0, n) == n, boost::test_tools::tolerance(1e-15));
  BOOST_TEST(node_porosity(0.0, 0.0, 1.0, n) == 1.0);
  BOOST_TEST(node_porosity(1.0, 1.0, 0.0, n) == 1.0);
  // Incompressible grains: a skeleton compressed to 0.9 of its volume, saturated or half saturated,
  // has the porosity 1 − (1 − n)/0.9 (its pores shrink by all the volume it lost).
  BOOST_TEST(node_porosity(1.0, 0.9, 0.9, n) == 1.0 - (1.0 - n) / 0.9, boost::test_tools::tolerance(1e-15));
  BOOST_TEST(node_porosity(1.0, 0.9, 0.45, n) == 1.0 - (1.0 - n) / 0.9, boost::test_tools::tolerance(1e-15));
  BOOST_TEST(node_drag(cE, 0.5, 1.0, half, n) * q / half == cE * 0.5 * q / n, boost::test_tools::tolerance(1e-12));
}

// [Klár 2016: Hencky energy] Under F = diag(1.1, 0.95) rotated by R, τ = R diag(2μ ε + λ tr ε) Rᵀ
// with ε = (log 1.1, log 0.95).
BOOST_AUTO_TEST_CASE(the_hencky_stress_of_a_rotated_stretch_is_the_closed_form) {
  const SandModel m = SandModel::from(2, 1e6, 0.3, 30.0, true);
  const double c = std::cos(0.4), s = std::sin(0.4);
  Mat<2> R;
  R << c, -s, s, c;
  const Vec<2> eps(std::log(1.1), std::log(0.95));
  const Mat<2> F = R * Vec<2>(1.1, 0.95).asDiagonal();
  const Vec<2> t = 2.0 * m.mu * eps + Vec<2>::Constant(m.lambda * eps.sum());
  const Mat<2> expected = R * t.asDiagonal() * R.transpose();
  BOOST_TEST((hencky_kirchhoff<2>(F, m) - expected).norm() <= 1e-9 * expected.norm());
}

// [Klár 2016: Lamé parameters] from Young's modulus E and Poisson's ratio ν: in 3-D a bar stretched
// by the log strain ε along x and contracted by −ν ε across carries the uniaxial stress E ε and
// none across; in 2-D (plane strain, no strain out of the plane) the same holds with ν/(1 − ν) and
// E/(1 − ν²). The Hencky stress is linear in the log strain, so these hold to round-off at any ε.
BOOST_AUTO_TEST_CASE(youngs_modulus_and_poissons_ratio_give_the_uniaxial_stress) {
  const double E = 2e6, nu = 0.3, eps = 0.02;
  const SandModel m3 = SandModel::from(3, E, nu, 30.0, true);
  const Mat<3> F3 = Vec<3>(std::exp(eps), std::exp(-nu * eps), std::exp(-nu * eps)).asDiagonal();
  const Mat<3> tau3 = hencky_kirchhoff<3>(F3, m3);
  BOOST_TEST(tau3(0, 0) == E * eps, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(std::abs(tau3(1, 1)) <= 1e-12 * E * eps);
  BOOST_TEST(std::abs(tau3(2, 2)) <= 1e-12 * E * eps);
  const SandModel m2 = SandModel::from(2, E, nu, 30.0, true);
  const Mat<2> F2 = Vec<2>(std::exp(eps), std::exp(-nu / (1.0 - nu) * eps)).asDiagonal();
  const Mat<2> tau2 = hencky_kirchhoff<2>(F2, m2);
  BOOST_TEST(tau2(0, 0) == E / (1.0 - nu * nu) * eps, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(std::abs(tau2(1, 1)) <= 1e-12 * E * eps);
}

// [Klár 2016: return mapping] A compressed trial outside the cone lands on it (‖τ̂‖ = −α tr τ) with
// its trace kept; an expanded one goes to the apex, at c cot φ of isotropic tension with cohesion;
// a trial inside stays.
BOOST_AUTO_TEST_CASE(the_return_mapping_lands_on_the_cone_or_its_apex) {
  const SandModel m = SandModel::from(2, 1e6, 0.3, 30.0, false);
  const Vec<2> shear(-0.01, 0.002);  // compressed, sheared far beyond the cone
  const Projection<2> on = project_drucker_prager<2>(shear, 0.0, 0.0, m);
  const Mat<2> tau = hencky_kirchhoff<2>(Mat<2>::Identity(), on.eps, m);
  const Mat<2> dev = tau - tau.trace() / 2.0 * Mat<2>::Identity();
  BOOST_TEST(dev.norm() == -m.alpha * tau.trace(), boost::test_tools::tolerance(1e-10));
  BOOST_TEST(on.eps.sum() == shear.sum(), boost::test_tools::tolerance(1e-12));
  const Vec<2> inside(-0.01, -0.009);
  BOOST_TEST((project_drucker_prager<2>(inside, 0.0, 0.0, m).eps - inside).norm() == 0.0);
  const double c = 500.0;
  const Projection<2> tip = project_drucker_prager<2>(Vec<2>(0.01, 0.0), c, 0.0, m);
  const Mat<2> tau_tip = hencky_kirchhoff<2>(Mat<2>::Identity(), tip.eps, m);
  BOOST_TEST(tau_tip(0, 0) == c * m.cot_phi, boost::test_tools::tolerance(1e-10));
  BOOST_TEST(tau_tip(1, 1) == c * m.cot_phi, boost::test_tools::tolerance(1e-10));
  // The cone slope of the plane is Mohr-Coulomb's: |σ1 − σ2| = sin φ |σ1 + σ2| on the cone.
  BOOST_TEST(std::abs(tau(0, 0) - tau(1, 1)) == std::sin(pi / 6.0) * -tau.trace(), boost::test_tools::tolerance(1e-10));
}

/// The Kirchhoff stress of one sand point (E = 3.537e5 Pa, ν = 0.3, the suite's sand) after steady
/// simple shear: F^E starts isotropically compressed (log strain −0.003 on each axis), then takes
/// 4000 steps of F^E ← (𝟙 + Δt ∇v) F^E with Δt ∂v_x/∂y = 1e-4 (a shear of 0.4, far beyond the
/// elastic strain), each followed by the return mapping as MpmSolver::plasticity does it.
Mat<2> simple_shear_stress(double phi) {
  const SandModel m = SandModel::from(2, 3.537e5, 0.3, phi, true);
  Mat<2> Fe = std::exp(-0.003) * Mat<2>::Identity(), step = Mat<2>::Identity();
  step(0, 1) = 1e-4;
  double vc = 0.0;
  for (int k = 0; k < 4000; ++k) {
    const Svd<2> s = svd<2>(step * Fe);
    const Projection<2> p = project_drucker_prager<2>(s.sigma.array().log().matrix(), 0.0, vc, m);
    vc = p.volume_correction;
    Fe = s.U * Vec<2>(p.eps.array().exp().matrix()).asDiagonal() * s.V.transpose();
  }
  return hencky_kirchhoff<2>(Fe, m);
}

// [Klár 2016: return mapping] [Davis 1968: non-associated flow in simple shear] The return mapping
// keeps the trace (no dilatancy, ψ = 0), so steady simple shear turns the deviator coaxial with the
// shearing, τ_xx = τ_yy within 1 %, and the shearing plane carries τ_xy/−τ_yy = sin φ within 1 %
// (Davis: tan φ* = sin φ cos ψ / (1 − sin φ sin ψ)), not Mohr-Coulomb's tan φ, which the plane cone
// reaches only on a plane that is not the one shearing. A layer flowing on a slope therefore keeps
// flowing down to tan θ = sin φ (26.6 deg for φ = 30 deg, 18.9 for 20, 29.8 for 35): the reason the
// suite's MPM sand piles come to rest below φ (cases/angle_of_repose).
// [Klár 2016: cone slope α] In 3-D the cone ‖τ̂‖_F = −α tr τ passes through the compression corners
// of the Mohr-Coulomb pyramid: a triaxial compression state (σ_a, σ_a, σ_b), σ_b < σ_a < 0, at
// Mohr-Coulomb's limit σ_a − σ_b = −(σ_a + σ_b) sin φ lies on it, and a triaxial extension state
// (σ_b, σ_b, σ_a) at the same limit lies inside it (the cone is inscribed between the two corners).
BOOST_AUTO_TEST_CASE(the_3d_cone_passes_through_mohr_coulombs_compression_corners) {
  for (const double phi : {20.0, 30.0, 35.0, 45.0}) {
    const double s = std::sin(phi * pi / 180.0);
    const double sa = -(1.0 - s), sb = -(1.0 + s);  // σ_a − σ_b = 2s = −(σ_a + σ_b) s
    const auto cone_ratio = [&](const Vec<3>& sigma) {
      const Vec<3> dev = (sigma.array() - sigma.sum() / 3.0).matrix();
      return dev.norm() / (-sigma.sum());  // ‖τ̂‖_F / (−tr τ), α on the cone
    };
    const double alpha = cone_slope(3, phi);
    BOOST_TEST(cone_ratio(Vec<3>(sa, sa, sb)) == alpha, boost::test_tools::tolerance(1e-12));
    BOOST_TEST(cone_ratio(Vec<3>(sb, sb, sa)) < alpha);
  }
}

BOOST_AUTO_TEST_CASE(steady_simple_shear_carries_sin_phi_on_the_shearing_plane) {
  for (const double phi : {20.0, 30.0, 35.0}) {
    const Mat<2> tau = simple_shear_stress(phi);
    const double ratio = tau(0, 1) / -tau(1, 1), s = std::sin(phi * pi / 180.0);
    BOOST_TEST_MESSAGE("simple shear at phi " << phi << ": tau_xy/-tau_yy " << ratio << " (sin phi " << s
                                              << ", tan phi " << std::tan(phi * pi / 180.0) << "), tau_xx/tau_yy "
                                              << tau(0, 0) / tau(1, 1));
    BOOST_TEST(ratio == s, boost::test_tools::tolerance(0.01));
    BOOST_TEST(tau(0, 0) / tau(1, 1) == 1.0, boost::test_tools::tolerance(0.01));
  }
}

// [Tampubolon 2017: eqs. 26-27] The volume the projection adds on expansion is stored and given
// back on the next compression: a trial dilated by 0.01 goes to the apex and stores 0.01; a
// compression of 0.004 then still projects to the apex, leaving 0.006; one of 0.01 more is elastic
// again by the 0.004 beyond what was owed, with nothing left stored.
BOOST_AUTO_TEST_CASE(the_volume_correction_stores_the_dilation_and_gives_it_back) {
  const SandModel m = SandModel::from(2, 1e6, 0.3, 30.0, true);
  const Projection<2> a = project_drucker_prager<2>(Vec<2>(0.006, 0.004), 0.0, 0.0, m);
  BOOST_TEST(a.eps.norm() == 0.0);
  BOOST_TEST(a.volume_correction == 0.01, boost::test_tools::tolerance(1e-12));
  const Projection<2> b = project_drucker_prager<2>(Vec<2>(-0.002, -0.002), 0.0, a.volume_correction, m);
  BOOST_TEST(b.eps.norm() == 0.0);
  BOOST_TEST(b.volume_correction == 0.006, boost::test_tools::tolerance(1e-12));
  const Projection<2> c = project_drucker_prager<2>(Vec<2>(-0.005, -0.005), 0.0, b.volume_correction, m);
  BOOST_TEST(c.eps.sum() == -0.004, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(std::abs(c.volume_correction) <= 1e-15);
  const SandModel off = SandModel::from(2, 1e6, 0.3, 30.0, false);
  BOOST_TEST(project_drucker_prager<2>(Vec<2>(0.006, 0.004), 0.0, 0.0, off).volume_correction == 0.0);
}

// [Klár 2016: plasticity in log-strain space] The return mapping changes the stretch and keeps the
// orientation: F^E = U Σ Vᵀ returns as U exp(ε) Vᵀ, so F^E = R S (R a rotation, S a stretch along
// the axes) returns as R S' with S' along the same axes. A block of cohesionless sand without
// gravity, every F^E a stretch turned by 30 deg, takes one substep short enough (1e-9 s) that the
// grid does not deform it measurably: pulled apart (S = diag(1.01, 1.02)) the sand cannot carry
// the tension and F^E becomes the rotation R itself to 1e-9; sheared beyond the cone, squeezed
// along one axis and stretched along the other (S = diag(0.96, 1.02)), it yields and Rᵀ F^E stays
// diagonal to 1e-9. (Rebuilding F^E as V exp(ε) Uᵀ would turn the body's stretch the other way.)
BOOST_AUTO_TEST_CASE(the_return_mapping_keeps_the_orientation_of_a_turned_stretch) {
  const Params<2> p = box(0.2, 0.2, 0.01);
  const double a = pi / 6.0;
  Mat<2> R;
  R << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  for (const Vec<2>& stretch : {Vec<2>(1.01, 1.02), Vec<2>(0.96, 1.02)}) {
    const bool tension = stretch.minCoeff() > 1.0;
    Particles<2> ps;
    fill<2>(ps, Vec<2>(0.05, 0.05), Vec<2>(0.15, 0.15), 0.005, 1800.0, Phase::Sand);
    for (Mat<2>& F : ps.Fe) F = R * stretch.asDiagonal();
    MpmSolver<2> solver(p, ps);
    solver.substep(1e-9);
    double off_frame = 0.0, yielded = 1.0;
    for (const Mat<2>& F : solver.particles().Fe) {
      const Mat<2> S = R.transpose() * F;
      off_frame = std::max(off_frame, tension ? (F - R).cwiseAbs().maxCoeff() : std::max(std::abs(S(0, 1)), std::abs(S(1, 0))));
      yielded = std::min(yielded, (S.diagonal() - stretch).cwiseAbs().maxCoeff());
    }
    BOOST_TEST(off_frame <= 1e-9);
    BOOST_TEST(yielded >= 1e-3);  // the projection moved every particle's stretch
  }
}

// [Tampubolon 2017: cohesion] A cohesive block (c0 = 2 kPa) at rest without gravity stays
// undeformed: F^E = 𝟙 to 1e-10 after 1000 steps, J = 1, nothing stored as volume correction. (A
// cone apex on the compressive side would project the block's zero strain and squeeze it.)
BOOST_AUTO_TEST_CASE(a_cohesive_block_at_rest_without_gravity_keeps_its_elastic_gradient) {
  Params<2> p = box(0.2, 0.2, 0.01);
  p.cohesion = 2000.0;
  Particles<2> ps;
  fill<2>(ps, Vec<2>(0.05, 0.0), Vec<2>(0.15, 0.1), 0.005, 1800.0, Phase::Sand);
  MpmSolver<2> solver(p, ps);
  const double dt = solver.stable_step();
  for (int k = 0; k < 1000; ++k) solver.substep(dt);
  double worst = 0.0;
  for (std::size_t i = 0; i < solver.particles().size(); ++i) {
    worst = std::max(worst, (solver.particles().Fe[i] - Mat<2>::Identity()).cwiseAbs().maxCoeff());
    worst = std::max({worst, std::abs(solver.particles().J[i] - 1.0), std::abs(solver.particles().vc[i])});
  }
  BOOST_TEST(worst <= 1e-10);
}

// [Stomakhin 2013: Coulomb friction at colliding grid nodes] The wall rule removes only a velocity
// into the wall. A cohesive block resting on the floor, without gravity, released upwards at
// 0.5 m/s: the floor's nodes carry a velocity leaving the wall, which is kept, so over 20
// substeps the block's momentum stays to round-off (APIC transfers and the internal forces keep
// it). Released downwards, the floor takes momentum from it in the first substep.
BOOST_AUTO_TEST_CASE(a_block_leaving_the_floor_keeps_its_momentum) {
  Params<2> p = box(0.2, 0.2, 0.01);
  p.cohesion = 2000.0;
  Particles<2> start;
  fill<2>(start, Vec<2>(0.05, 0.0), Vec<2>(0.15, 0.05), 0.005, 1800.0, Phase::Sand);
  const auto momentum = [](const Particles<2>& ps) {
    Vec<2> P = Vec<2>::Zero();
    for (std::size_t i = 0; i < ps.size(); ++i) P += ps.m[i] * ps.v[i];
    return P;
  };
  for (const double vy : {0.5, -0.5}) {
    Particles<2> ps = start;
    for (auto& v : ps.v) v = Vec<2>(0.0, vy);
    const Vec<2> P0 = momentum(ps);
    MpmSolver<2> solver(p, ps);
    const double dt = solver.stable_step();
    for (int k = 0; k < (vy > 0.0 ? 20 : 1); ++k) solver.substep(dt);
    const double change = (momentum(solver.particles()) - P0).norm() / P0.norm();
    if (vy > 0.0) BOOST_TEST(change <= 1e-12);
    else BOOST_TEST(change >= 1e-2);
  }
}

// [Stomakhin 2013: Coulomb friction at colliding grid nodes] Each side has its own rule
// (Params::rough[2d + side]). A block of sand (F^E = 𝟙: no stress), no gravity, moving at
// (1, ±0.5) m/s into the floor or into the ceiling, one substep: the nodes at and beyond the wall
// lose their normal velocity and, on a rough side (μ = 0.5), their tangential velocity by μ times
// that (1 m/s is far above the 0.25 m/s lost, so none stops). APIC's transfers keep the grid's
// momentum, so the block's momentum changes by ΔP_x = −μ |ΔP_y| on a rough side and by ΔP_x = 0 on
// a smooth one (1e-10 of |P|). Only one of floor and ceiling is rough at a time.
BOOST_AUTO_TEST_CASE(each_side_of_the_box_has_its_own_wall_friction) {
  const double mu = 0.5;
  const auto momentum = [](const Particles<2>& ps) {
    Vec<2> P = Vec<2>::Zero();
    for (std::size_t i = 0; i < ps.size(); ++i) P += ps.m[i] * ps.v[i];
    return P;
  };
  for (const bool ceiling : {false, true})
    for (const int rough_side : {2, 3}) {  // the floor (y−) or the ceiling (y+) is the rough one
      BOOST_TEST_CONTEXT("into the " << (ceiling ? "ceiling" : "floor") << ", rough side " << rough_side) {
        Params<2> p = box(0.2, 0.2, 0.01);
        p.rough = {false, false, false, false};
        p.rough[rough_side] = true;
        p.wall_friction = mu;
        Particles<2> ps;
        const double y0 = ceiling ? 0.15 : 0.0;
        fill<2>(ps, Vec<2>(0.05, y0), Vec<2>(0.15, y0 + 0.05), 0.005, 1800.0, Phase::Sand);
        for (auto& v : ps.v) v = Vec<2>(1.0, ceiling ? 0.5 : -0.5);
        const Vec<2> P0 = momentum(ps);
        MpmSolver<2> solver(p, ps);
        solver.substep(1e-4);
        const Vec<2> dP = momentum(solver.particles()) - P0;
        const bool rough = rough_side == (ceiling ? 3 : 2);
        BOOST_TEST(std::abs(dP[1]) >= 0.05 * std::abs(P0[1]));  // the wall stopped the sand next to it
        BOOST_TEST(std::abs(dP[0] - (rough ? -mu * std::abs(dP[1]) : 0.0)) <= 1e-10 * P0.norm());
      }
    }
}

// [Hu 2018: MLS-MPM force] A column of elastic sand (cohesion high enough never to yield, ν = 0)
// 0.2 m wide and H = 0.1 m high, ρ = 1800 kg/m^3, on grids of 0.01 and 0.005 m (CB-Geo's
// hydrostatic column), damped to rest: the bottom row's σ_yy is −ρ g H to within 5 % on the coarse
// grid and the error at least nearly halves under refinement (first order or better).
BOOST_AUTO_TEST_CASE(an_elastic_column_at_rest_carries_its_weight, *test::long_run()) {
  const double coarse = column_stress_error<2>(0.2, 0.1, 0.01), fine = column_stress_error<2>(0.2, 0.1, 0.005);
  BOOST_TEST_MESSAGE("elastic column: bottom sigma_yy error " << coarse << " (h 0.01), " << fine << " (h 0.005)");
  BOOST_TEST(coarse <= 0.05);
  BOOST_TEST(fine <= 0.6 * coarse);
}

// [Terzaghi 1943: effective stress] [Zienkiewicz & Shiomi 1984: u-U equations] The same column with
// water in its pores (n = 0.4, water to its top) carries its buoyant weight: the sand's effective
// σ_yy at the bottom row is −(ρ − (1 − n) ρ_w) g H within 5 % on the coarse grid. The grains take the
// share 1 − n_i of the pore pressure's force (node_porosity); without it they would carry −ρ g H,
// 50 % more.
BOOST_AUTO_TEST_CASE(a_saturated_elastic_column_carries_its_buoyant_weight, *test::long_run()) {
  const double error = column_stress_error<2>(0.2, 0.1, 0.01, true);
  BOOST_TEST_MESSAGE("saturated column: bottom effective sigma_yy error " << error << " (h 0.01)");
  BOOST_TEST(error <= 0.05);
}

// [Zienkiewicz & Shiomi 1984: u-U equations] A still pond 0.1 m deep over a bed 0.1 m deep held by a
// clamp, its pores full (n = 0.4), damped to rest: the pore pressure of the bed's sand over the bed's
// middle half is ρ_w g d of each particle's depth d within 3 % on average, and the water rests (every
// speed below 1e-3 √(g d)). The water takes the share n_i of the pore pressure's force, so it feels
// −n ∇p in the pores and −∇p above; were its own partial stress −n p all it felt, n p would be
// continuous across the bed's surface and the bed's pore pressure would rise towards p/n.
BOOST_AUTO_TEST_CASE(a_still_pond_over_a_held_bed_keeps_the_hydrostatic_pore_pressure) {
  const double dx = 0.005, n = 0.4, bed = 0.1, pond = 0.1;
  Params<2> p = box(0.1, 0.3, 2.0 * dx);
  p.gravity = Vec<2>(0.0, -9.81);
  p.porosity = n;
  p.drag = drag_per_volume(n, 1000.0, 9.81, 1e-3);
  p.relax_until = 1e9;
  p.relax_rate = 40.0;
  p.clamps.push_back({Vec<2>(-1.0, -1.0), Vec<2>(1.0, bed + 1.5 * p.grid.h)});
  Particles<2> ps;
  fill<2>(ps, Vec<2>::Zero(), Vec<2>(0.1, bed), dx, 1800.0, Phase::Sand);
  const std::size_t sand = ps.size();
  fill_pores<2>(ps, Vec<2>::Zero(), Vec<2>(0.1, bed), dx, n);
  fill<2>(ps, Vec<2>(0.0, bed), Vec<2>(0.1, bed + pond), dx, 1000.0, Phase::Water);
  MpmSolver<2> solver(p, ps);
  while (solver.time() < 0.5) solver.advance(1e-3);
  double sum = 0.0, speed = 0.0;
  int count = 0;
  for (std::size_t i = 0; i < solver.particles().size(); ++i) {
    speed = std::max(speed, solver.particles().v[i].norm());
    const double y = solver.particles().x[i][1];
    if (i < sand && y > 0.25 * bed && y < 0.75 * bed) {
      sum += solver.particles().pressure[i] / (1000.0 * 9.81 * (pond + bed - y));
      ++count;
    }
  }
  BOOST_TEST_MESSAGE("pond over a held bed: mid-bed pore pressure over rho g d " << sum / count << ", largest speed "
                                                                                 << speed << " m/s");
  BOOST_TEST(std::abs(sum / count - 1.0) <= 0.03);
  BOOST_TEST(speed <= 1e-3 * std::sqrt(9.81 * (pond + bed)));
}

// The same column in 3-D (a 0.04 m square footprint, the coarse grid): the dimension-generic
// transfers and the 3-D cone carry the weight as in 2-D.
BOOST_AUTO_TEST_CASE(an_elastic_column_at_rest_carries_its_weight_in_3d, *test::long_run()) {
  const double error = column_stress_error<3>(0.04, 0.1, 0.01);
  BOOST_TEST_MESSAGE("elastic column 3-D: bottom sigma_zz error " << error << " (h 0.01)");
  BOOST_TEST(error <= 0.05);
}

// [Tampubolon 2017: saturation, cohesion c(φ)] Saturation is the water's share of the pores, not
// an indicator of where the two grids overlap: sand and water particles on the same lattice, the
// water carrying n or n/2 of the sand's volume, give every sand particle a saturation of 1 or 1/2
// after one step (to round-off), and the cohesion c0 (1 − s) follows.
BOOST_AUTO_TEST_CASE(saturation_is_the_water_fraction_of_the_pores) {
  for (const double fill_fraction : {1.0, 0.5}) {
    Params<2> p = box(0.2, 0.2, 0.02);
    p.cohesion = 1000.0;
    p.porosity = 0.4;
    Particles<2> ps;
    fill<2>(ps, Vec<2>(0.05, 0.05), Vec<2>(0.15, 0.15), 0.01, 1800.0, Phase::Sand);
    const std::size_t sand = ps.size();
    fill<2>(ps, Vec<2>(0.05, 0.05), Vec<2>(0.15, 0.15), 0.01, 1000.0, Phase::Water);
    for (std::size_t i = sand; i < ps.size(); ++i) ps.V0[i] *= fill_fraction * p.porosity;
    MpmSolver<2> solver(p, ps);
    solver.substep(1e-4);
    for (std::size_t i = 0; i < sand; ++i) {
      BOOST_TEST(solver.particles().saturation[i] == fill_fraction, boost::test_tools::tolerance(1e-12));
      BOOST_TEST(solver.cohesion(i) == 1000.0 * (1.0 - fill_fraction), boost::test_tools::tolerance(1e-9));
    }
  }
}

// [Zienkiewicz & Shiomi 1984: u-U equations] [Tampubolon 2017: weakly compressible water] The pore
// water's pressure in a mixture is its Cauchy pressure, Tait's p(ρ0/J) = B ((1/J)^γ − 1), not the
// Kirchhoff −τ = J p. Water filling the pores of a sand block (n = 0.4, on the sand's lattice),
// compressed to J = 0.95, no gravity, one substep of 1e-6 s: every water particle carries
// p = 24 684 Pa (c = 20 m/s, γ = 7) to 1e-12, and every sand particle reads that pore pressure
// through the grid to 1e-10 (the water's nodal pressure is uniform and the weights add up to 1).
BOOST_AUTO_TEST_CASE(the_pore_waters_pressure_is_its_cauchy_pressure) {
  Params<2> p = box(0.2, 0.2, 0.02);
  p.porosity = 0.4;
  Particles<2> ps;
  fill<2>(ps, Vec<2>(0.05, 0.05), Vec<2>(0.15, 0.15), 0.01, 1800.0, Phase::Sand);
  const std::size_t sand = ps.size();
  fill_pores<2>(ps, Vec<2>(0.05, 0.05), Vec<2>(0.15, 0.15), 0.01, p.porosity);
  const double J = 0.95;
  for (std::size_t i = sand; i < ps.size(); ++i) ps.J[i] = J;
  const double B = 1000.0 * p.eos.sound_speed * p.eos.sound_speed / p.eos.gamma;
  const double expected = B * (std::pow(1.0 / J, p.eos.gamma) - 1.0);
  BOOST_TEST(expected == 24684.16, boost::test_tools::tolerance(1e-6));
  MpmSolver<2> solver(p, ps);
  solver.substep(1e-6);
  double water_error = 0.0, sand_error = 0.0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    double& worst = i < sand ? sand_error : water_error;
    worst = std::max(worst, std::abs(solver.particles().pressure[i] / expected - 1.0));
  }
  BOOST_TEST(water_error <= 1e-12);
  BOOST_TEST(sand_error <= 1e-10);
}

/// The period of an elastic bar along x, its left end at x = 0.5 m: L = 1 m long, 0.1 m thick,
/// E = 100 Pa, ρ = 1, ν = 0, 40 cells along it, started in the mode v_x = v0 shape(ξ) (ξ the distance
/// from the left end, v0 = c/1000) and run for five periods T, from the zero crossings of its modal
/// velocity Σ v_x shape(ξ0). `clamped`: the nodes at x ≤ 0.5 m hold the left end.
/// With ν = 0, λ = 0 and τ_xx = 2μ ε_xx = E ε_xx whatever the thickness does, so the plane-strain bar
/// carries uniaxial waves at c = √(E/ρ) exactly.
template <class Shape>
double bar_period(Shape shape, double T, bool clamped) {
  const double E = 100.0, rho = 1.0, v0 = std::sqrt(E / rho) / 1000.0;
  Params<2> p = box(2.0, 1.0, 0.025);
  p.sand = SandModel::from(2, E, 0.0, 30.0, true);
  p.sand_density = rho;
  p.cohesion = 1e6;
  if (clamped) p.clamps.push_back({Vec<2>(-1.0, -1.0), Vec<2>(0.5, 2.0)});
  Particles<2> ps;
  fill<2>(ps, Vec<2>(0.5, 0.45), Vec<2>(1.5, 0.55), 0.0125, rho, Phase::Sand);
  std::vector<double> mode(ps.size());
  for (std::size_t i = 0; i < ps.size(); ++i) {
    mode[i] = shape(ps.x[i][0] - 0.5);
    ps.v[i][0] = v0 * mode[i];
  }
  MpmSolver<2> solver(p, ps);
  const double dt = solver.stable_step();
  std::vector<double> crossings;
  double previous = 1.0;
  while (solver.time() < 5.0 * T) {
    solver.substep(dt);
    double a = 0.0;
    for (std::size_t i = 0; i < solver.particles().size(); ++i) a += solver.particles().v[i][0] * mode[i];
    if ((a < 0.0) != (previous < 0.0)) crossings.push_back(solver.time() - dt * a / (a - previous));
    previous = a;
  }
  BOOST_REQUIRE(crossings.size() >= 8u);
  return 2.0 * (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
}

// The elastic core and the APIC transfers: a free-free elastic bar (bar_period: L = 1 m, c = 10 m/s)
// started in its first mode, v = v0 cos(π ξ/L), rings with the analytic period 2L/c to within 1 %
// over five periods. (Its energy is not gated: the transfers dissipate it at first order in the
// cell width.)
BOOST_AUTO_TEST_CASE(a_free_elastic_bar_rings_with_its_analytic_period) {
  const double T = 2.0 * 1.0 / 10.0;
  const double period = bar_period([](double xi) { return std::cos(pi * xi); }, T, false);
  BOOST_TEST_MESSAGE("free bar: period " << period << " s against " << T << " s");
  BOOST_TEST(std::abs(period / T - 1.0) <= 0.01);
}

// The same bar held at one end by a clamp (the grid nodes at and beyond its left end hold the sand
// at rest, in tension as in compression; Bardenhagen 2002's fixed-free bar): started in its first
// mode, v = v0 sin(π ξ/(2L)), it rings with the analytic period 4L/c to within 1 % over five periods.
BOOST_AUTO_TEST_CASE(a_fixed_free_elastic_bar_rings_with_its_analytic_period) {
  const double T = 4.0 * 1.0 / 10.0;
  const double period = bar_period([](double xi) { return std::sin(0.5 * pi * xi); }, T, true);
  BOOST_TEST_MESSAGE("fixed-free bar: period " << period << " s against " << T << " s");
  BOOST_TEST(std::abs(period / T - 1.0) <= 0.01);
}

// [Tampubolon 2017: eq. 22, immovable sand] Water on a node whose sand a clamp holds: its velocity
// falls by exactly m_w/(m_w + Δt ξ) per step, and under a steady force f it settles at the Darcy
// velocity f/ξ (to 1e-12), the balance a seepage through a fixed bed needs.
BOOST_AUTO_TEST_CASE(water_on_clamped_sand_decays_to_the_drag_balance) {
  const double m_w = 0.5, xi = 40.0, dt = 1e-3, a = dt * xi;
  Vec<2> v(0.3, -1.0);
  const Vec<2> v0 = v;
  exchange_with_clamped_sand<2>(m_w, a, v);
  BOOST_TEST((v - m_w / (m_w + a) * v0).norm() <= 1e-15 * v0.norm());
  const Vec<2> f(0.0, -2.0);
  for (int step = 0; step < 20000; ++step) {
    v += dt * f / m_w;
    exchange_with_clamped_sand<2>(m_w, a, v);
  }
  BOOST_TEST((v - f / xi).norm() <= 1e-12 * (f / xi).norm());
}

/// The volume Σ J V0 of a dry column of aspect ratio 2 (0.1 m wide, 0.2 m high, φ = 19.8°, Klár et
/// al.'s sand, rough floor and back wall) after it has collapsed for 0.6 s, over its initial volume.
double collapsed_volume_ratio(bool volume_correction) {
  const double h = 0.02, dx = 0.01;
  Params<2> p = box(0.6, 0.3, h);
  p.sand = SandModel::from(2, 3.537e5, 0.3, 19.8, volume_correction);
  p.sand_density = 2650.0;
  p.gravity = Vec<2>(0.0, -9.81);
  p.rough = {true, false, true, false};
  p.wall_friction = std::tan(19.8 * pi / 180.0);
  Particles<2> ps;
  fill<2>(ps, Vec<2>(0.0, 0.0), Vec<2>(0.1, 0.2), dx, 2650.0, Phase::Sand);
  MpmSolver<2> solver(p, ps);
  while (solver.time() < 0.6) solver.advance(1e-3);
  double volume = 0.0;
  for (std::size_t i = 0; i < solver.particles().size(); ++i) volume += solver.particles().J[i] * solver.particles().V0[i];
  return volume / (0.1 * 0.2);
}

// [Tampubolon 2017: eqs. 26-27] A collapsing dry column keeps its volume within 5 % with the volume
// correction, and gains less than classical Drucker-Prager sand, which keeps every plastic dilation.
BOOST_AUTO_TEST_CASE(a_collapsing_dry_column_keeps_its_volume_with_the_correction) {
  const double on = collapsed_volume_ratio(true), off = collapsed_volume_ratio(false);
  BOOST_TEST_MESSAGE("collapsed column volume ratio: " << on << " with the correction, " << off << " without");
  BOOST_TEST(std::abs(on - 1.0) <= 0.05);
  BOOST_TEST(on - 1.0 < off - 1.0);
}

/// The degree of consolidation of a saturated elastic column measured at the time factors `Tv`
/// (ascending), from its settlement s (the mean sinking of the loaded top row) over the final one of
/// linear theory, s_∞ = q H / E_oed. The column: H = 0.1 m of sand (ρ = 1800 kg/m^3, E = 1e5 Pa,
/// ν = 0.3, a cohesion it never reaches), 0.02 m wide between smooth walls on a smooth floor (closed
/// to the water: it drains at its top only), its pores full (n = 0.4, K = 1e-3 m/s), no gravity;
/// a load q = 1e-3 E_oed on its top row of sand particles from t = 0, without damping. In plane
/// strain with the walls holding it laterally E_oed = λ + 2μ, and c_v = K E_oed / (ρ_w g), g = 9.81
/// m/s² the unit weight of K's definition. The water's bulk modulus ρ_w c² (c = 80 m/s) is about
/// 120 n E_oed, so the load first goes to the pore water, the settlement it allows at once is under
/// 1 % of s_∞, and the undrained mixture rings about the loaded state by that much.
std::vector<double> consolidation_degrees(const std::vector<double>& Tv) {
  const double H = 0.1, width = 0.02, h = 0.01, dx = h / 2.0, n = 0.4, K = 1e-3;
  Params<2> p = box(width, 2.0 * H, h);
  p.sand = SandModel::from(2, 1e5, 0.3, 30.0, true);
  p.cohesion = 1e7;
  p.wet_cohesion_loss = false;
  p.porosity = n;
  p.drag = drag_per_volume(n, 1000.0, 9.81, K);
  p.eos.sound_speed = 80.0;
  const double E_oed = p.sand.lambda + 2.0 * p.sand.mu, q = 1e-3 * E_oed, cv = K * E_oed / (1000.0 * 9.81);
  Particles<2> ps;
  fill<2>(ps, Vec<2>::Zero(), Vec<2>(width, H), dx, 1800.0, Phase::Sand);
  std::vector<std::size_t> top;
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (ps.x[i][1] > H - dx) {
      ps.load[i] = Vec<2>(0.0, -q * dx);
      top.push_back(i);
    }
  fill_pores<2>(ps, Vec<2>::Zero(), Vec<2>(width, H), dx, n);
  MpmSolver<2> solver(p, ps);
  std::vector<double> U;
  for (const double T : Tv) {
    solver.advance(T * H * H / cv - solver.time());
    double sink = 0.0, pore = 0.0;
    for (const std::size_t i : top) sink += (ps.x[i][1] - solver.particles().x[i][1]) / static_cast<double>(top.size());
    int count = 0;
    for (std::size_t i = 0; i < solver.particles().size(); ++i)
      if (solver.particles().is_sand(i)) pore += solver.particles().pressure[i], ++count;
    U.push_back(sink / (q * H / E_oed));
    BOOST_TEST_MESSAGE("consolidation at T_v " << T << ": U " << U.back() << " from the settlement, "
                                               << 1.0 - pore / count / q << " from the pore pressure, analytic "
                                               << analytic::terzaghi_consolidation_degree(T) << " ("
                                               << solver.time() << " s)");
  }
  return U;
}

// [Terzaghi 1943: consolidation] The analytic series at its landmarks: U = 0.5 at T_v = 0.197 and
// 0.9 at T_v = 0.848 (to the three digits of the tables), 1 − 8/π² e^{−π² T/4} once the first term
// dominates, and nothing at T_v = 0.
BOOST_AUTO_TEST_CASE(the_consolidation_series_passes_its_landmarks) {
  BOOST_TEST(analytic::terzaghi_consolidation_degree(0.197) == 0.5, boost::test_tools::tolerance(1e-3));
  BOOST_TEST(analytic::terzaghi_consolidation_degree(0.848) == 0.9, boost::test_tools::tolerance(1e-3));
  const double late = 1.0 - 8.0 / (pi * pi) * std::exp(-pi * pi * 2.0 / 4.0);
  BOOST_TEST(analytic::terzaghi_consolidation_degree(2.0) == late, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(analytic::terzaghi_consolidation_degree(0.0) == 0.0);
}

// [Terzaghi 1943: consolidation] [Zienkiewicz & Shiomi 1984: u-U equations] [Tampubolon 2017: drag
// c_E] A saturated elastic column under a surface load, draining at its top (consolidation_degrees):
// the degree of consolidation from its settlement is the analytic series' within 0.03 at T_v =
// 0.197 (U = 0.5) and 0.848 (U = 0.9). The pore water carries the load at first because the
// grains share the pore pressure's force (1 − n_i); it drains at the pace of the drag, c_v ∝ 1/c_E.
BOOST_AUTO_TEST_CASE(a_loaded_saturated_column_consolidates_as_terzaghi_says) {
  const std::vector<double> Tv = {0.197, 0.848};
  const std::vector<double> U = consolidation_degrees(Tv);
  for (std::size_t k = 0; k < Tv.size(); ++k)
    BOOST_TEST(std::abs(U[k] - analytic::terzaghi_consolidation_degree(Tv[k])) <= 0.03);
}

// [Mohr-Coulomb: unconfined strength] [Rankine: critical height] The method references' table of
// Rankine heights (ρ_b = 1600 kg/m^3) to its millimetre: 0.088 m and 0.221 m for c = 200 and 500 Pa
// at φ = 30°, 0.098 m and 0.245 m at 35°, the heights where the active thrust on the face vanishes.
// The solver's plane cone with its apex at c cot φ is that Mohr-Coulomb material: a uniaxial
// compression σ_yy = −q, σ_xx = 0 is elastic (left as it is) at q = 0.99 q_u and projected at
// 1.01 q_u, q_u = 2c tan(45° + φ/2).
BOOST_AUTO_TEST_CASE(the_plane_cone_has_mohr_coulombs_unconfined_strength_and_rankines_height) {
  const double rho = 1600.0, g = 9.81;
  BOOST_TEST(std::abs(analytic::rankine_critical_height(200.0, 30.0, rho, g) - 0.088) <= 5e-4);
  BOOST_TEST(std::abs(analytic::rankine_critical_height(500.0, 30.0, rho, g) - 0.221) <= 5e-4);
  BOOST_TEST(std::abs(analytic::rankine_critical_height(200.0, 35.0, rho, g) - 0.098) <= 5e-4);
  BOOST_TEST(std::abs(analytic::rankine_critical_height(500.0, 35.0, rho, g) - 0.245) <= 5e-4);
  for (const double phi : {30.0, 35.0}) {
    const SandModel m = SandModel::from(2, 1e6, 0.3, phi, true);
    const double c = 200.0, qu = analytic::unconfined_strength(c, phi);
    // the active thrust ∫_0^H (ρ g z K_a − 2c √K_a) dz, K_a = tan²(45° − φ/2), at H = H_c
    const double Hc = analytic::rankine_critical_height(c, phi, rho, g);
    const double Ka = std::pow(std::tan((45.0 - phi / 2.0) * pi / 180.0), 2);
    BOOST_TEST(std::abs(0.5 * rho * g * Hc * Hc * Ka - 2.0 * c * std::sqrt(Ka) * Hc) <= 1e-12 * rho * g * Hc * Hc);
    for (const double factor : {0.99, 1.01}) {
      // the log strain of the Kirchhoff stress (0, −q): τ_i = 2μ ε_i + λ tr ε
      const Vec<2> tau(0.0, -factor * qu);
      const double tr = tau.sum() / (2.0 * m.mu + 2.0 * m.lambda);
      const Vec<2> eps = ((tau.array() - m.lambda * tr) / (2.0 * m.mu)).matrix();
      const double change = (project_drucker_prager<2>(eps, c, 0.0, m).eps - eps).norm();
      if (factor < 1.0)
        BOOST_TEST(change == 0.0);
      else
        BOOST_TEST(change > 1e-3 * eps.norm());
    }
  }
}

/// The moist sand of the wet cut: the bulk density and a cohesion of the method references' Rankine
/// table (docs/references.md §13), and the cut's width and grid cell [m].
constexpr double cut_density = 1600.0, cut_cohesion = 200.0, cut_width = 0.2, cut_cell = 0.01;

/// A vertical cut in plane strain: sand (E = 1e6 Pa, ν = 0.3, friction angle φ, cohesion
/// cut_cohesion) cut_width wide on a rough floor (Coulomb, μ = tan φ) against a smooth wall at x = 0,
/// a mirror, so that it stands for a block twice as wide; its face at x = cut_width is free, with
/// 0.25 m of clear floor in front. The solver's cohesion is Mohr-Coulomb's c (the plane cone is
/// Mohr-Coulomb's, cone_slope), so Rankine's H_c applies to it as it is.
Params<2> cut_params(double phi) {
  Params<2> p = box(cut_width + 0.25, 0.2, cut_cell);
  p.sand = SandModel::from(2, 1e6, 0.3, phi, true);
  p.sand_density = cut_density;
  p.cohesion = cut_cohesion;
  p.gravity = Vec<2>(0.0, -9.81);
  p.rough = {false, false, true, false};
  p.wall_friction = std::tan(phi * pi / 180.0);
  return p;
}

/// The cut's particles, H high exactly: two per cell across, layers of equal thickness (at most half
/// a cell) upwards, row by row, so that the last one is the top corner of the face.
Particles<2> cut_particles(double H) {
  const double dx = cut_cell / 2.0;
  const long nx = std::lround(cut_width / dx), ny = std::lround(std::ceil(H / dx));
  const double dy = H / static_cast<double>(ny);
  Particles<2> ps;
  for (long j = 0; j < ny; ++j)
    for (long i = 0; i < nx; ++i)
      ps.add(Vec<2>((i + 0.5) * dx, (j + 0.5) * dy), cut_density * dx * dy, dx * dy, Phase::Sand);
  return ps;
}

/// How far particle k has moved from `start`, over H.
double moved(const MpmSolver<2>& solver, const Particles<2>& start, std::size_t k, double H) {
  return (solver.particles().x[k] - start.x[k]).norm() / H;
}

/// The top corner's displacement over H of a dry cut (cut_params, cut_particles) H high, 1 s after
/// gravity comes on at rest, undamped: over six free-fall times √(2H/g) of the cuts below.
double dry_cut_corner_moved(double phi, double H) {
  const Particles<2> ps = cut_particles(H);
  MpmSolver<2> solver(cut_params(phi), ps);
  while (solver.time() < 1.0 - 1e-9) solver.advance(1e-2);
  return moved(solver, ps, ps.size() - 1, H);
}

// [Rankine: critical height] A vertical cut of moist sand (c = 200 Pa, ρ_b = 1600 kg/m^3, plane
// strain) with gravity switched on at rest: at 0.75 H_c it stands (the top corner of its face has
// moved less than 1 % of H after 1 s, elastic settling included) and at 1.25 H_c it falls (the
// corner has moved more than a quarter of H), at φ = 30° and 35° (H_c = 0.0883 and 0.0979 m): the
// method references' ±25 %. The heights follow the friction angle through tan(45° + φ/2).
BOOST_AUTO_TEST_CASE(a_cut_stands_below_rankines_height_and_falls_above_it, *test::long_run()) {
  for (const double phi : {30.0, 35.0}) {
    const double Hc = analytic::rankine_critical_height(cut_cohesion, phi, cut_density, 9.81);
    const double low = dry_cut_corner_moved(phi, 0.75 * Hc), high = dry_cut_corner_moved(phi, 1.25 * Hc);
    BOOST_TEST_MESSAGE("cut at phi " << phi << " (H_c " << Hc << " m): corner moved " << low << " H at 0.75 H_c, "
                                     << high << " H at 1.25 H_c");
    BOOST_TEST(low < 0.01);
    BOOST_TEST(high > 0.25);
  }
}

/// What wet_cut measured: the corner's displacement over H when the water started and at the end,
/// the time from the water's start until the corner had moved a quarter of H (−1 if it had not), and
/// the mean saturation of the sand then.
struct Wetting {
  double moved_dry = 0.0, moved = 0.0, fall_time = -1.0, saturation = 0.0;
};

/// The wetting of a standing cut (cut_params and cut_particles, φ = 30°, H = 0.75 H_c): 0.3 s under
/// gravity dry (s = 0, c = c0), then every 0.05 s a row of water parcels at rest on its top, all of it
/// but the two cells at the face (no water runs down the face), at `rate` [m/s] of water depth per
/// time; the water seeps in through the exchange (porosity 0.4, K = 0.05 m/s, cfl 0.2), and the
/// cohesion is c0 (1 − s) unless `cohesion_loss` is off. The solver is rebuilt from its particles and
/// the new parcels (the particles carry the state it keeps). Runs until the corner has moved a
/// quarter of H or `until` s of wetting have passed.
Wetting wet_cut(double rate, bool cohesion_loss, double until) {
  const double H = 0.75 * analytic::rankine_critical_height(cut_cohesion, 30.0, cut_density, 9.81);
  const double dx = cut_cell / 2.0, interval = 0.05, chunk = 0.01;
  Params<2> p = cut_params(30.0);
  const Particles<2> start = cut_particles(H);
  const std::size_t corner = start.size() - 1;
  std::optional<MpmSolver<2>> solver(std::in_place, p, start);
  while (solver->time() < 0.3 - 1e-9) solver->advance(chunk);
  Wetting w;
  w.moved_dry = moved(*solver, start, corner, H);
  p.drag = drag_per_volume(p.porosity, 1000.0, 9.81, 0.05);
  p.cfl = 0.2;
  p.wet_cohesion_loss = cohesion_loss;
  const long chunks = std::lround(until / chunk), per_interval = std::lround(interval / chunk);
  for (long k = 0; k < chunks && w.fall_time < 0.0; ++k) {
    if (k % per_interval == 0) {
      Particles<2> ps = solver->particles();
      const std::size_t first = ps.size();
      fill<2>(ps, Vec<2>(0.0, H), Vec<2>(cut_width - 2.0 * cut_cell, H + dx), dx, 1000.0, Phase::Water);
      for (std::size_t i = first; i < ps.size(); ++i) {
        ps.m[i] *= rate * interval / dx;
        ps.V0[i] *= rate * interval / dx;
      }
      solver.emplace(p, ps);
    }
    solver->advance(chunk);
    w.moved = moved(*solver, start, corner, H);
    if (w.moved > 0.25) w.fall_time = static_cast<double>(k + 1) * chunk;
  }
  for (std::size_t i = 0; i < start.size(); ++i) w.saturation += solver->particles().saturation[i] / start.size();
  return w;
}

// [Tampubolon 2017: cohesion c(φ)] [Rankine: critical height] Seepage brings a standing cut down: the
// cut at 0.75 H_c stands dry (corner moved under 1 % of H), then water is supplied on its top at
// 0.02 m/s and seeps in (wet_cut); the saturation rises, c0 (1 − s) falls and the cut falls (the
// corner moves a quarter of H) within 2 s. Its twin whose cohesion stays c0 under the same water has
// moved less than 1 % of H by then: the water's weight and drag alone do not bring it down. A faster
// inflow, 0.04 m/s, brings it down sooner (the method references: time to collapse decreasing
// with the inflow rate).
BOOST_AUTO_TEST_CASE(seeping_water_brings_a_standing_cut_down_and_faster_inflow_sooner, *test::long_run()) {
  const Wetting slow = wet_cut(0.02, true, 2.0);
  const Wetting twin = wet_cut(0.02, false, slow.fall_time > 0.0 ? slow.fall_time : 2.0);
  const Wetting fast = wet_cut(0.04, true, 2.0);
  BOOST_TEST_MESSAGE("wet cut: dry corner moved " << slow.moved_dry << " H; inflow 0.02 m/s: fell after "
                                                  << slow.fall_time << " s (mean saturation " << slow.saturation
                                                  << "), twin with c0 kept: moved " << twin.moved << " H (saturation "
                                                  << twin.saturation << "); inflow 0.04 m/s: fell after "
                                                  << fast.fall_time << " s (saturation " << fast.saturation << ")");
  BOOST_TEST(slow.moved_dry < 0.01);
  BOOST_TEST(slow.fall_time > 0.0);
  BOOST_TEST(twin.moved < 0.01);
  BOOST_TEST(fast.fall_time > 0.0);
  BOOST_TEST(fast.fall_time < slow.fall_time);
}

// [Tampubolon 2017: weakly compressible water] The water's Kirchhoff stress is J times its Cauchy
// stress −p 𝟙, p being Tait's pressure at the compressed density ρ0/J: B ((1/J)^γ − 1) with
// B = ρ0 c²/γ. At J = 0.95 (5 % compressed) the factor J is far above round-off, so a Cauchy stress
// passed off as the Kirchhoff one fails; isotropic, and free of stress at J = 1.
BOOST_AUTO_TEST_CASE(the_waters_kirchhoff_stress_is_j_times_its_tait_pressure) {
  EquationOfState eos;
  eos.sound_speed = 20.0;
  eos.gamma = 7.0;
  const double rho0 = 1000.0, B = rho0 * 20.0 * 20.0 / 7.0;
  for (const double J : {0.95, 0.99}) {
    const double p = B * (std::pow(1.0 / J, 7.0) - 1.0);
    const Mat<3> tau = water_kirchhoff<3>(J, rho0, eos);
    BOOST_TEST((tau + J * p * Mat<3>::Identity()).norm() <= 1e-12 * J * p);
    const Mat<2> tau2 = water_kirchhoff<2>(J, rho0, eos);
    BOOST_TEST((tau2 + J * p * Mat<2>::Identity()).norm() <= 1e-12 * J * p);
  }
  BOOST_TEST(water_kirchhoff<3>(1.0, rho0, eos).norm() == 0.0);
}

// What MPM reports of its water (MpmMethod::particles): a particle's density is its mass over its
// volume now, m/(J V0), and its pressure is Tait's at that density. A water block compressed to
// J = 0.95 reports ρ0/J = 1052.63 kg/m^3 (1e-12) and B ((1/J)^γ − 1) = 24 684 Pa (c = 20 m/s, γ = 7;
// 1e-10: seen through the grid, a uniform field is unchanged).
BOOST_AUTO_TEST_CASE(a_compressed_water_block_reports_its_density_and_taits_pressure) {
  const Params<2> p = box(0.2, 0.2, 0.01);
  Particles<2> ps;
  fill<2>(ps, Vec<2>(0.05, 0.05), Vec<2>(0.15, 0.15), 0.005, 1000.0, Phase::Water);
  const double J = 0.95;
  for (double& j : ps.J) j = J;
  const MpmMethod<2> method(MpmSolver<2>(p, ps), 1e-3, 0.01, std::vector<std::uint8_t>(ps.size(), 0));
  const ParticleView<2> view = method.particles();
  const double B = 1000.0 * p.eos.sound_speed * p.eos.sound_speed / p.eos.gamma;
  const double p_tait = B * (std::pow(1.0 / J, p.eos.gamma) - 1.0);
  double density_error = 0.0, pressure_error = 0.0;
  for (std::size_t i = 0; i < view.size(); ++i) {
    density_error = std::max(density_error, std::abs(view.density[i] / (1000.0 / J) - 1.0));
    pressure_error = std::max(pressure_error, std::abs(view.pressure[i] / p_tait - 1.0));
  }
  BOOST_TEST(view.size() == ps.size());
  BOOST_TEST(density_error <= 1e-12);
  BOOST_TEST(pressure_error <= 1e-10);
}

// A runaway speed (one sand particle at 1e6 m/s) shrinks the CFL substep to 4e-9 s, 2.5e5 substeps
// in the case's step of 1 ms: the method's step stops at once with a blow-up naming the step (1,
// counted from 1), the fastest particle and its speed, before any substep, instead of stalling. At
// 100 m/s (32 substeps) it steps.
BOOST_AUTO_TEST_CASE(a_runaway_speed_stops_the_step_as_a_blow_up) {
  const Params<2> p = box(0.1, 0.1, 0.01);
  Particles<2> ps;
  fill<2>(ps, Vec<2>(0.02, 0.0), Vec<2>(0.06, 0.04), 0.005, 1800.0, Phase::Sand);
  const std::vector<std::uint8_t> no_bed(ps.size(), 0);
  ps.v[7] = Vec<2>(0.0, 1e6);
  MpmMethod<2> runaway(MpmSolver<2>(p, ps), 1e-3, 0.01, no_bed);
  try {
    runaway.step();
    BOOST_ERROR("a step of 2.5e5 substeps ran");
  } catch (const BlowUpError& e) {
    BOOST_TEST(e.step() == 1);
    BOOST_TEST(e.particle() == 7);
    BOOST_TEST(std::string(e.what()).find("field 'v'") != std::string::npos, e.what());
    BOOST_TEST(std::string(e.what()).find("1e+06 m/s") != std::string::npos, e.what());
  }
  BOOST_TEST(runaway.time() == 0.0);
  ps.v[7] = Vec<2>(0.0, 100.0);
  MpmMethod<2> fast(MpmSolver<2>(p, ps), 1e-3, 0.01, no_bed);
  fast.step();
  BOOST_TEST(fast.own_steps().value() == 32);
  BOOST_TEST(fast.time() == 1e-3, boost::test_tools::tolerance(1e-12));
}

// Per-node gathers and per-particle scatters: a sand bed with water over part of it (the exchange
// active), large enough for the loops to run in parallel, is bitwise the same after 30 steps on
// one and on two threads. The particles are stored water, lower sand, upper sand, water, so the
// two halves of a static split each hold one sand layer and the nodes between the layers would
// take their sums in another order if the particles added into them.
BOOST_AUTO_TEST_CASE(one_and_two_threads_are_bitwise_identical) {
  Params<2> p = box(0.4, 0.3, 0.005);
  p.gravity = Vec<2>(0.0, -9.81);
  p.rough = {true, false, true, false};
  p.wall_friction = 0.5;
  p.drag = drag_per_volume(0.4, 1000.0, 9.81, 1e-3);
  Particles<2> ps;
  fill<2>(ps, Vec<2>(0.25, 0.0), Vec<2>(0.35, 0.2), 0.0025, 1000.0, Phase::Water);
  fill<2>(ps, Vec<2>(0.0, 0.0), Vec<2>(0.2, 0.05), 0.0025, 1800.0, Phase::Sand);
  fill<2>(ps, Vec<2>(0.0, 0.05), Vec<2>(0.2, 0.1), 0.0025, 1800.0, Phase::Sand);
  fill<2>(ps, Vec<2>(0.1, 0.05), Vec<2>(0.2, 0.25), 0.0025, 1000.0, Phase::Water);
  BOOST_REQUIRE(ps.size() == 9600u);
  const int saved = omp_get_max_threads();
  std::string checksum[2];
  double saturation = 0.0;
  for (const int threads : {1, 2}) {
    omp_set_num_threads(threads);
    MpmSolver<2> solver(p, ps);
    for (int k = 0; k < 30; ++k) solver.substep(2e-4);
    checksum[threads - 1] = state_checksum<2>(solver.particles().x, solver.particles().v);
    for (const double s : solver.particles().saturation) saturation = std::max(saturation, s);
  }
  omp_set_num_threads(saved);
  BOOST_TEST(saturation > 0.0);  // the two phases share nodes
  BOOST_TEST(checksum[0] == checksum[1]);
}

BOOST_AUTO_TEST_SUITE_END()
