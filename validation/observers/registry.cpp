// The observers a case file can name in "validation": {"observer": NAME}. Add new ones here.
#include "observer.hpp"

namespace sc {

template <int D> std::unique_ptr<Observer<D>> make_hydrostatic_observer(const ObserverContext&);
template <int D> std::unique_ptr<Observer<D>> make_dam_break_observer(const ObserverContext&);
template <int D> std::unique_ptr<Observer<D>> make_scene_observer(const ObserverContext&);
template <int D> std::unique_ptr<Observer<D>> make_column_collapse_observer(const ObserverContext&);
template <int D> std::unique_ptr<Observer<D>> make_rigid_cluster_observer(const ObserverContext&);
template <int D> std::unique_ptr<Observer<D>> make_rigid_spin_observer(const ObserverContext&);
template <int D> std::unique_ptr<Observer<D>> make_angle_of_repose_observer(const ObserverContext&);
template <int D> std::unique_ptr<Observer<D>> make_darcy_column_observer(const ObserverContext&);
template <int D> std::unique_ptr<Observer<D>> make_green_ampt_observer(const ObserverContext&);
template <int D> std::unique_ptr<Observer<D>> make_capillary_rise_observer(const ObserverContext&);

JsonObject validation_block(const ObserverContext& ctx) {
  JsonObject o(ctx.spec.validation, "/validation", ctx.spec.file);
  o.mark_used("observer");
  o.mark_used("convergence");
  o.mark_used("uniform_twin");
  o.mark_used("dry_twin");
  return o;
}

template <int D>
std::unique_ptr<Observer<D>> make_observer(const ObserverContext& ctx) {
  JsonObject o(ctx.spec.validation, "/validation", ctx.spec.file);
  const std::string name = o.one_of("observer", {"hydrostatic", "dam_break", "darcy_column", "column_collapse", "rigid_cluster", "rigid_spin", "angle_of_repose", "scene", "green_ampt", "capillary_rise"});
  if (name == "hydrostatic") return make_hydrostatic_observer<D>(ctx);
  if (name == "scene") return make_scene_observer<D>(ctx);
  if (name == "column_collapse") return make_column_collapse_observer<D>(ctx);
  if (name == "rigid_cluster") return make_rigid_cluster_observer<D>(ctx);
  if (name == "rigid_spin") return make_rigid_spin_observer<D>(ctx);
  if (name == "angle_of_repose") return make_angle_of_repose_observer<D>(ctx);
  if (name == "darcy_column") return make_darcy_column_observer<D>(ctx);
  if (name == "green_ampt") return make_green_ampt_observer<D>(ctx);
  if (name == "capillary_rise") return make_capillary_rise_observer<D>(ctx);
  return make_dam_break_observer<D>(ctx);
}

template std::unique_ptr<Observer<2>> make_observer<2>(const ObserverContext&);
template std::unique_ptr<Observer<3>> make_observer<3>(const ObserverContext&);

}  // namespace sc
