#include "simulator/sph_method.hpp"

#include "io/vtu_writer.hpp"
#include "porous/porous_volume.hpp"
#include "scene/scene_builder.hpp"

namespace sc {

template <int D>
SphMethod<D>::SphMethod(Simulator<D> sim, std::string parameters_hash, double spacing)
    : sim_(std::move(sim)), parameters_hash_(std::move(parameters_hash)), spacing_(spacing) {}

template <int D>
const ParticleSet<D>& SphMethod<D>::state() const {
  const Decomposition<D>* dd = sim_.decomposition();
  if (!dd) return sim_.particles();
  if (gathered_revision_ != sim_.revision()) {
    gathered_ = dd->gather(sim_.particles());
    gathered_revision_ = sim_.revision();
  }
  return gathered_;
}

template <int D>
ParticleView<D> SphMethod<D>::particles() const {
  const ParticleSet<D>& ps = state();
  ParticleView<D> view;
  view.x = {ps.x.data(), ps.size()};
  view.v = {ps.v.data(), ps.size()};
  view.m = ps.m;
  view.phase = ps.phase;
  view.id = ps.id;
  view.pressure = ps.p;
  view.density = ps.rho;
  view.support = ps.h;
  if (!sim_.params().porous) return view;
  view.porosity = ps.porosity;
  view.held_water = ps.absorbed;
  view.leaving_water = ps.emit_store;
  view.saturation = ps.saturation;
  pore_water_pressure_.resize(ps.size());
  for (std::size_t i = 0; i < ps.size(); ++i) pore_water_pressure_[i] = ps.pore_pressure[i] - ps.capillary[i];
  view.pore_water_pressure = pore_water_pressure_;
  pore_volume_.resize(ps.size());
  for (std::size_t i = 0; i < ps.size(); ++i)
    pore_volume_[i] = ps.porosity[i] > 0.0 ? ps.porosity[i] * porous_volume(ps, i) : 0.0;
  view.pore_volume = pore_volume_;
  return view;
}

template <int D>
std::vector<StageTime> SphMethod<D>::stage_times() const {
  std::vector<StageTime> out;
  for (std::size_t s = 0; s < stage_names.size(); ++s)
    out.push_back({std::string(stage_names[s]), sim_.timers().seconds(static_cast<Stage>(s)), 0});
  return out;
}

template <int D>
std::string SphMethod<D>::vtu_frame() const {
  return vtu_document(state());
}

template <int D>
std::string SphMethod<D>::last_good_frame() const {
  const Decomposition<D>* dd = sim_.decomposition();
  return vtu_document(dd ? dd->gather(sim_.last_good()) : sim_.last_good());
}

template <int D>
void SphMethod<D>::write_checkpoint(const std::string& path, const json& run) const {
  CheckpointState s;
  s.dimension = D;
  s.spacing = spacing_;
  s.parameters_hash = parameters_hash_;
  s.time = sim_.time();
  s.step = sim_.steps();
  s.last_dt = sim_.last_dt();
  s.run = run;
  const ParticleSet<D>& all = state();  // collective when decomposed; rank 0 writes
  const Decomposition<D>* dd = sim_.decomposition();
  if (!dd || dd->comm().rank() == 0) sc::write_checkpoint(path, all, s);
}

namespace {

/// SPH at t = 0 on `ranks` (none: one process).
template <int D>
std::unique_ptr<Method<D>> start_sph(const CaseSpec& spec, double dx, std::optional<Comm> ranks) {
  try {
    Simulator<D> sim(build_scene<D>(spec, dx), SimulationParams::from_case(spec, dx), ranks);
    return std::make_unique<SphMethod<D>>(std::move(sim), spec.parameters_hash, dx);
  } catch (const BlowUpError& e) {
    throw InputError(spec.file, "/domain", "every initial particle (blocks and tank wall layers) must lie inside "
                                           "the domain; particle " + std::to_string(e.particle()) + " does not");
  }
}

/// SPH from a checkpoint on `ranks` (none: one process).
template <int D>
std::unique_ptr<Method<D>> continue_sph(const CaseSpec& spec, double dx, const Checkpoint& c, std::optional<Comm> ranks) {
  Simulator<D> sim(restore_particles<D>(c), SimulationParams::from_case(spec, dx), ranks);
  sim.set_clock(c.state.time, c.state.step);
  sim.set_last_dt(c.state.last_dt);
  return std::make_unique<SphMethod<D>>(std::move(sim), spec.parameters_hash, dx);
}

}  // namespace

template <int D>
std::unique_ptr<Method<D>> make_sph_method(const CaseSpec& spec, double dx) {
  return start_sph<D>(spec, dx, std::nullopt);
}

template <int D>
std::unique_ptr<Method<D>> resume_sph_method(const CaseSpec& spec, double dx, const Checkpoint& c) {
  return continue_sph<D>(spec, dx, c, std::nullopt);
}

template <int D>
std::unique_ptr<Method<D>> make_decomposed_sph_method(const CaseSpec& spec, double dx) {
  return start_sph<D>(spec, dx, Comm::world());
}

template <int D>
std::unique_ptr<Method<D>> resume_decomposed_sph_method(const CaseSpec& spec, double dx, const Checkpoint& c) {
  return continue_sph<D>(spec, dx, c, Comm::world());
}

template class SphMethod<2>;
template class SphMethod<3>;
template std::unique_ptr<Method<2>> make_sph_method<2>(const CaseSpec&, double);
template std::unique_ptr<Method<3>> make_sph_method<3>(const CaseSpec&, double);
template std::unique_ptr<Method<2>> resume_sph_method<2>(const CaseSpec&, double, const Checkpoint&);
template std::unique_ptr<Method<3>> resume_sph_method<3>(const CaseSpec&, double, const Checkpoint&);
template std::unique_ptr<Method<2>> make_decomposed_sph_method<2>(const CaseSpec&, double);
template std::unique_ptr<Method<3>> make_decomposed_sph_method<3>(const CaseSpec&, double);
template std::unique_ptr<Method<2>> resume_decomposed_sph_method<2>(const CaseSpec&, double, const Checkpoint&);
template std::unique_ptr<Method<3>> resume_decomposed_sph_method<3>(const CaseSpec&, double, const Checkpoint&);

}  // namespace sc
