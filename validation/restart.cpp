#include "restart.hpp"

#include <cstdio>

#include "scene/scene_builder.hpp"

namespace sc {

namespace {

json frame_log_json(const FrameLog& log) {
  json frames = json::array();
  for (const auto& [time, name] : log.frames) frames.push_back({time, name});
  return {{"frames", frames}, {"next_frame", log.next_frame}};
}

FrameLog read_frame_log(const json& run, const std::string& file) {
  JsonObject o(run, "/run", file);
  FrameLog log;
  log.next_frame = o.number("next_frame");
  const json& frames = o.raw("frames");
  if (!frames.is_array()) o.fail("frames", "must be an array of [time, file name]");
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const json& f = frames[k];
    if (!f.is_array() || f.size() != 2 || !f[0].is_number() || !f[1].is_string())
      throw InputError(file, "/run/frames/" + std::to_string(k), "must be [time, file name]");
    log.frames.emplace_back(f[0].get<double>(), f[1].get<std::string>());
  }
  o.finish();
  return log;
}

/// Rejects a checkpoint written by another case or at another spacing.
void check_same_run(const Checkpoint& c, const CaseSpec& spec, double dx) {
  if (c.state.parameters_hash != spec.parameters_hash)
    throw InputError(c.file, "/parameters_hash",
                     "checkpoint was written for other case parameters (hash " + c.state.parameters_hash +
                         ", case " + spec.file + " has " + spec.parameters_hash + ")");
  if (c.state.spacing != dx)
    throw InputError(c.file, "/spacing", "checkpoint spacing " + json(c.state.spacing).dump() +
                                             " m differs from the run's " + json(dx).dump() + " m");
}

}  // namespace

template <int D>
Simulator<D> start_simulator(const CaseSpec& spec, double dx, const std::string& resume_from, FrameLog& log) {
  const SimulationParams params = SimulationParams::from_case(spec, dx);
  if (resume_from.empty()) {
    try {
      return Simulator<D>(build_scene<D>(spec, dx), params);
    } catch (const BlowUpError& e) {
      throw InputError(spec.file, "/domain", "every initial particle (blocks and tank wall layers) must lie inside "
                                             "the domain; particle " + std::to_string(e.particle()) + " does not");
    }
  }
  const Checkpoint c = read_checkpoint(resume_from);
  check_same_run(c, spec, dx);
  log = read_frame_log(c.state.run, c.file);
  Simulator<D> sim(restore_particles<D>(c), params);
  sim.set_clock(c.state.time, c.state.step);
  sim.set_last_dt(c.state.last_dt);
  return sim;
}

template <int D>
void write_run_checkpoint(const std::string& path, const Simulator<D>& sim, const CaseSpec& spec, double dx,
                          const FrameLog& log) {
  CheckpointState s;
  s.dimension = D;
  s.spacing = dx;
  s.parameters_hash = spec.parameters_hash;
  s.time = sim.time();
  s.step = sim.steps();
  s.last_dt = sim.last_dt();
  s.run = frame_log_json(log);
  write_checkpoint(path, sim.particles(), s);
}

std::string checkpoint_name(long step) {
  char name[40];
  std::snprintf(name, sizeof name, "checkpoint_%08ld.ckpt", step);
  return name;
}

template Simulator<2> start_simulator<2>(const CaseSpec&, double, const std::string&, FrameLog&);
template Simulator<3> start_simulator<3>(const CaseSpec&, double, const std::string&, FrameLog&);
template void write_run_checkpoint<2>(const std::string&, const Simulator<2>&, const CaseSpec&, double, const FrameLog&);
template void write_run_checkpoint<3>(const std::string&, const Simulator<3>&, const CaseSpec&, double, const FrameLog&);

}  // namespace sc
