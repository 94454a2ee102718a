#include "restart.hpp"

#include <cstdio>

#include "method/registry.hpp"

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

}  // namespace

template <int D>
std::unique_ptr<Method<D>> start_method(const CaseSpec& spec, double dx, const std::string& resume_from, FrameLog& log,
                                        bool decompose) {
  if (resume_from.empty()) return make_method<D>(spec, dx, decompose);
  json run;
  std::unique_ptr<Method<D>> method = resume_method<D>(spec, dx, resume_from, run, decompose);
  log = read_frame_log(run, resume_from);
  return method;
}

template <int D>
void write_run_checkpoint(const std::string& path, const Method<D>& method, const FrameLog& log) {
  method.write_checkpoint(path, frame_log_json(log));
}

std::string checkpoint_name(long step) {
  char name[40];
  std::snprintf(name, sizeof name, "checkpoint_%08ld.ckpt", step);
  return name;
}

template std::unique_ptr<Method<2>> start_method<2>(const CaseSpec&, double, const std::string&, FrameLog&, bool);
template std::unique_ptr<Method<3>> start_method<3>(const CaseSpec&, double, const std::string&, FrameLog&, bool);
template void write_run_checkpoint<2>(const std::string&, const Method<2>&, const FrameLog&);
template void write_run_checkpoint<3>(const std::string&, const Method<3>&, const FrameLog&);

}  // namespace sc
