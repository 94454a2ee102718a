#include "sand/sand_section.hpp"

namespace sc {

SandParams read_sand(JsonObject o) {
  SandParams s;
  s.rest_density = o.positive("rest_density");
  s.friction_angle_deg = o.in_range("friction_angle", 0.0, 90.0, true);
  s.cohesion = o.non_negative("cohesion", 0.0);
  s.wet_cohesion_loss = o.boolean("wet_cohesion_loss", true);
  s.viscosity = o.non_negative("viscosity", 0.0);
  s.wall_friction = o.has("wall_friction") ? o.non_negative("wall_friction", 0.0) : -1.0;
  s.contact_damping = o.non_negative("contact_damping", 0.5);
  s.rigid_clusters = o.boolean("rigid_clusters", true);
  s.rigid_length = o.one_of("rigid_stress_length", {"spacing", "support"}, "spacing") == "spacing"
                       ? RigidStressLength::Spacing : RigidStressLength::Support;
  s.yield_surface = o.one_of("yield_surface", {"flow_consistent", "zhu_bridson"}, "flow_consistent") == "flow_consistent"
                        ? YieldSurface::FlowConsistent : YieldSurface::ZhuBridson;
  s.inertia = o.one_of("inertia_tensor", {"corrected", "printed"}, "corrected") == "corrected" ? InertiaForm::Corrected
                                                                                                 : InertiaForm::Printed;
  o.finish();
  return s;
}

}  // namespace sc
