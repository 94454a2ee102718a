// Any method's particles as a VTU document (ParaView): the fields of its ParticleView, the
// optional ones only when the method fills them. Methods without a particle container of their
// own (FLIP, DEM, MPM) write their frames with this.
#pragma once
#include <string>

#include "io/vtu_writer.hpp"
#include "method/method.hpp"

namespace sc {

template <int D>
std::string vtu_document(const ParticleView<D>& view) {
  return vtu_points_document<D>(view.x, [&](const auto& f) {
    f("velocity", view.v);
    f("mass", view.m);
    f("phase", view.phase);
    const auto optional = [&](const char* name, const auto& field) {
      if (!field.empty()) f(name, field);
    };
    optional("id", view.id);
    optional("pressure", view.pressure);
    optional("density", view.density);
    optional("support_radius", view.support);
    optional("porosity", view.porosity);
    optional("absorbed_water", view.held_water);
    optional("emit_store", view.leaving_water);
    optional("saturation", view.saturation);
    optional("pore_water_pressure", view.pore_water_pressure);
  });
}

}  // namespace sc
