// The "water" section of a case file: the water's forces, its equation of state and the numerical
// viscosity, read and checked (keys in cases/README.md). Like every physics folder, water/ owns its
// section's reader; case/case_file.cpp only calls it.
#pragma once
#include "io/json_reader.hpp"
#include "sph/equation_of_state.hpp"
#include "water/water_forces.hpp"

namespace sc {

struct WaterSection {
  WaterParams params;
  EquationOfState eos;
  /// Monaghan's α; when set, μ = α ρ0 h c / (2(D + 2)) at each spacing (h: support), so the
  /// numerical viscosity shrinks with the resolution. 0 = params.viscosity as given.
  double artificial_viscosity = 0.0;
};

/// Reads the "water" section. Throws InputError (file, JSON path, rule) on any problem, among them
/// both `viscosity` and `artificial_viscosity` given.
WaterSection read_water(JsonObject o);

}  // namespace sc
