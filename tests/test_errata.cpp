// The erratum switches (docs/equations.md §5) and `validate --errata` (validation/errata.hpp): each
// switch, merged into a case document, is read by its section's reader and selects the printed
// formula, which differs from the corrected one by the erratum's factor or sign: [thesis eq. 4],
// [thesis eq. 10], [thesis eq. 12a], [thesis eq. 22], [thesis eq. 25], [thesis eq. 28].
#include <boost/test/unit_test.hpp>
#include <cmath>

#include "errata.hpp"
#include "case/case_file.hpp"
#include "porous/pore_pressure.hpp"
#include "sand/sand_forces.hpp"
#include "sand/yield.hpp"

namespace sc {
namespace {

namespace tt = boost::test_tools;

std::string case_path(const std::string& name) { return std::string(SANDCASTLE_SOURCE_DIR) + "/cases/" + name + "/case.json"; }

/// The case as loaded with the erratum of `equation` merged in.
CaseSpec printed_case(const std::string& equation, const std::string& name) {
  for (const Erratum& e : errata_table())
    if (e.equation == equation) return load_case(patched_case_document(case_path(name), e.patch), case_path(name));
  BOOST_FAIL("no erratum " + equation);
  return {};
}

}  // namespace

BOOST_AUTO_TEST_SUITE(errata)

BOOST_AUTO_TEST_CASE(every_switch_is_read_and_changes_the_case_of_each_affected_case) {
  // Each erratum's merge patch loads on every case it affects, and moves its parameters (a switch
  // that no reader took would leave the parameters hash unchanged); the case file is untouched.
  for (const Erratum& e : errata_table())
    for (const std::string& name : e.cases) {
      const CaseSpec corrected = load_case(case_path(name));
      const CaseSpec printed = load_case(patched_case_document(case_path(name), e.patch), case_path(name));
      BOOST_TEST(printed.parameters_hash != corrected.parameters_hash, "eq " << e.equation << " on " << name);
      BOOST_TEST(load_case(case_path(name)).parameters_hash == corrected.parameters_hash);
    }
}

BOOST_AUTO_TEST_CASE(eq_4_switch_selects_muellers_halved_pressure) {
  BOOST_TEST(!load_case(case_path("hydrostatic")).water.mueller_half_pressure);
  BOOST_TEST(printed_case("4", "hydrostatic").water.mueller_half_pressure);
}

BOOST_AUTO_TEST_CASE(eq_10_switch_selects_the_printed_strength_k_1) {
  // [thesis eq. 10]: the printed yield surface has k = 1, the corrected one k = 3/√2.
  const CaseSpec corrected = load_case(case_path("column_collapse"));
  const CaseSpec printed = printed_case("10", "column_collapse");
  BOOST_TEST(yield_strength_factor(printed.sand.yield_surface) == 1.0);
  BOOST_TEST(yield_strength_factor(corrected.sand.yield_surface) / yield_strength_factor(printed.sand.yield_surface) ==
             3.0 / std::sqrt(2.0), tt::tolerance(1e-14));
}

BOOST_AUTO_TEST_CASE(eq_12a_switch_selects_the_support_and_scales_the_rigid_stress_by_h_over_s_squared) {
  // [thesis eq. 12a]: with the printed length (the support h = 2 s of a lattice particle) the
  // rigid stress is (h/s)² = 4 times the corrected one (the particle spacing s = V^(1/D)).
  const CaseSpec corrected = load_case(case_path("column_collapse"));
  const CaseSpec printed = printed_case("12a", "column_collapse");
  const double rho = 2650.0, s = rest_spacing<2>(rho * 0.01 * 0.01, rho), h = 2.0 * s, dt = 1e-4;
  const Mat<2> shear = (Mat<2>() << 0.0, 3.0, 3.0, 0.0).finished();
  const Mat<2> a = rigid_stress<2>(shear, rho, rigid_stress_length(corrected.sand.rigid_length, h, s), dt);
  const Mat<2> b = rigid_stress<2>(shear, rho, rigid_stress_length(printed.sand.rigid_length, h, s), dt);
  BOOST_TEST(s == 0.01, tt::tolerance(1e-14));
  BOOST_TEST(b(0, 1) == 4.0 * a(0, 1), tt::tolerance(1e-14));
  BOOST_TEST(a(0, 1) == -rho * s * s / dt * 3.0, tt::tolerance(1e-14));
}

BOOST_AUTO_TEST_CASE(eq_22_switch_selects_the_plain_gradient) {
  BOOST_TEST((load_case(case_path("green_ampt")).porous->gradient == PorousGradient::Corrected));
  BOOST_TEST((printed_case("22", "green_ampt").porous->gradient == PorousGradient::Lenaerts));
}

BOOST_AUTO_TEST_CASE(eq_25_switch_selects_the_inverted_ratio) {
  // [thesis eq. 25]: printed P^p = k^p S ((ρ0/ρ)^γ − 1), Lenaerts' k^p S ((ρ/ρ0)^γ − 1): under
  // compression the printed form is a suction where Lenaerts' is a pressure.
  const CaseSpec printed = printed_case("25", "wet_sand_collapse");
  BOOST_TEST(printed.porous->thesis_pore_pressure_ratio);
  BOOST_TEST(!load_case(case_path("wet_sand_collapse")).porous->thesis_pore_pressure_ratio);
  const double kp = 5e4, S = 0.6, rho = 2100.0, rho0 = 2000.0, gamma = 7.0;
  const double thesis = pore_pressure(kp, S, rho, rho0, gamma, printed.porous->thesis_pore_pressure_ratio);
  BOOST_TEST(thesis == kp * S * (std::pow(rho0 / rho, gamma) - 1.0), tt::tolerance(1e-14));
  BOOST_TEST(pore_pressure(kp, S, rho, rho0, gamma) == kp * S * (std::pow(rho / rho0, gamma) - 1.0), tt::tolerance(1e-14));
  BOOST_TEST(thesis < 0.0);
}

BOOST_AUTO_TEST_CASE(eq_28_switch_selects_the_literal_diffusion) {
  BOOST_TEST((printed_case("28", "green_ampt").porous->diffusion == PorousDiffusion::LenaertsLiteral));
  BOOST_TEST((load_case(case_path("green_ampt")).porous->diffusion == PorousDiffusion::Conserving));
}

BOOST_AUTO_TEST_SUITE_END()

}  // namespace sc
