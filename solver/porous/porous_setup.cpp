#include "porous/porous_setup.hpp"

#include "porous/diffusion.hpp"
#include "porous/porous_volume.hpp"
#include "porous/wet_density.hpp"

namespace sc {

PorousParams read_porous(JsonObject o, double water_density) {
  PorousParams p;
  p.fluid_density = water_density;
  p.porosity = o.in_range("porosity", 0.0, 1.0, true);
  p.permeability = o.positive("permeability");
  p.fluid_viscosity = o.positive("fluid_viscosity", 1e-3);
  p.capillary_constant = o.non_negative("capillary_constant", 0.0);
  p.capillary_exponent = o.in_range("capillary_exponent", 0.0, 1.0, false, 0.1);
  if (p.capillary_exponent <= 0.0) o.fail("capillary_exponent", "must be > 0");
  p.saturation_exponent = o.positive("saturation_exponent", 7.0);
  p.pore_stiffness = o.non_negative("pore_stiffness", 0.0);
  p.pore_gamma = o.in_range("pore_gamma", 1.0, 10.0, false, 7.0);
  p.stress_scale = o.non_negative("stress_scale", 1.0);
  p.initial_saturation = o.in_range("initial_saturation", 0.0, 1.0, false, 0.0);
  p.min_water_fraction = o.in_range("min_water_fraction", 0.0, 0.5, false, 0.01);
  p.create_fraction = o.in_range("create_fraction", 0.0, 1.0, false, 0.1);
  if (p.create_fraction <= p.min_water_fraction) o.fail("create_fraction", "must exceed min_water_fraction");
  p.gradient = o.one_of("gradient", {"corrected", "lenaerts"}, "corrected") == "corrected" ? PorousGradient::Corrected
                                                                                           : PorousGradient::Lenaerts;
  p.diffusion = o.one_of("diffusion", {"conserving", "lenaerts_literal"}, "conserving") == "conserving"
                    ? PorousDiffusion::Conserving : PorousDiffusion::LenaertsLiteral;
  p.thesis_pore_pressure_ratio = o.boolean("thesis_pore_pressure_ratio", false);
  o.finish();
  return p;
}

template <int D>
void derive_porous(PorousParams& p, double dx, double h, double water_mass, kernel::DensityKernel density_kernel) {
  p.density_kernel = density_kernel;
  p.spacing = dx;
  p.water_mass = water_mass;
  p.water_support = h;
  p.flux_length_factor = flux_length_factor<D>(dx, h, lattice_volume(p));
}

template <int D>
void init_porous(ParticleSet<D>& ps, const PorousParams& p) {
  ps.add_porous_fields();
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps.phase_of(i) == Phase::Water) continue;
    ps.porosity[i] = p.porosity;
    ps.saturation[i] = p.initial_saturation;
    ps.absorbed[i] = p.initial_saturation * p.fluid_density * p.porosity * porous_volume(ps, i);
    if (carries_held_water(ps, i)) take_in_held_water(ps, i, p.porosity, p.fluid_density);
  }
}

template void derive_porous<2>(PorousParams&, double, double, double, kernel::DensityKernel);
template void derive_porous<3>(PorousParams&, double, double, double, kernel::DensityKernel);
template void init_porous<2>(ParticleSet<2>&, const PorousParams&);
template void init_porous<3>(ParticleSet<3>&, const PorousParams&);

}  // namespace sc
