#include "water/water_section.hpp"

namespace sc {

WaterSection read_water(JsonObject o) {
  WaterSection w;
  w.params.rest_density = o.positive("rest_density");
  w.params.viscosity = o.non_negative("viscosity", 0.0);
  w.artificial_viscosity = o.non_negative("artificial_viscosity", 0.0);
  if (o.has("viscosity") && o.has("artificial_viscosity"))
    o.fail("artificial_viscosity", "give either viscosity (Pa s) or artificial_viscosity (alpha), not both");
  w.params.surface_tension = o.non_negative("surface_tension", 0.0);
  w.params.density_kernel = o.one_of("density_kernel", {"spiky", "poly6"}, "spiky") == "spiky"
                                ? kernel::DensityKernel::Spiky : kernel::DensityKernel::Poly6;
  w.params.gradient_correction = o.boolean("gradient_correction", true);
  w.params.mueller_half_pressure = o.boolean("mueller_half_pressure", false);
  const std::string eos = o.one_of("equation_of_state", {"tait", "linear"}, "tait");
  w.eos.kind = eos == "tait" ? EquationOfState::Kind::Tait : EquationOfState::Kind::Linear;
  w.eos.sound_speed = o.positive("sound_speed");
  w.eos.gamma = o.in_range("gamma", 1.0, 10.0, false, 7.0);
  w.eos.clamp_negative = o.boolean("clamp_negative_pressure", true);
  o.finish();
  return w;
}

}  // namespace sc
