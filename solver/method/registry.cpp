#include "method/registry.hpp"

#include <algorithm>

#include "dem/dem_method.hpp"
#include "flip/flip_method.hpp"
#include "io/checkpoint.hpp"
#include "mpm/mpm_method.hpp"
#include "simulator/sph_method.hpp"

namespace sc {

namespace {

/// One registered method: its case name, how it starts, how it resumes from a checkpoint (null for
/// a method that writes none), and how it checks its own "methods"/NAME parameters and the scene
/// against what it can run (null when the case's own sections are all it reads).
template <int D>
struct Entry {
  const char* name;
  std::unique_ptr<Method<D>> (*make)(const CaseSpec&, double);
  std::unique_ptr<Method<D>> (*resume)(const CaseSpec&, double, const Checkpoint&);
  void (*check)(const CaseSpec&);
};

/// Rejects a spinning block (blocks[].angular_velocity) for a method that starts its blocks at rest.
void check_blocks_at_rest(const CaseSpec& spec, const std::string& method) {
  for (std::size_t b = 0; b < spec.blocks.size(); ++b)
    if (!spec.blocks[b].angular_velocity.empty())
      throw InputError(spec.file, "/blocks/" + std::to_string(b) + "/angular_velocity",
                       "method \"" + method + "\" starts every block at rest; only \"sph\" reads angular_velocity");
}

void check_flip(const CaseSpec& spec) {
  read_flip_params(spec);
  check_blocks_at_rest(spec, "flip");
}
void check_dem(const CaseSpec& spec) {
  read_dem_params(spec);
  check_blocks_at_rest(spec, "dem");
}
void check_mpm(const CaseSpec& spec) {
  read_mpm_params(spec);
  check_blocks_at_rest(spec, "mpm");
}

/// Every method of this build. A new method adds its line here (and its own folder under solver/).
template <int D>
const std::vector<Entry<D>>& entries() {
  static const std::vector<Entry<D>> table = {
      {"sph", make_sph_method<D>, resume_sph_method<D>, nullptr},
      {"flip", make_flip_method<D>, nullptr, check_flip},
      {"dem", make_dem_method<D>, nullptr, check_dem},
      {"mpm", make_mpm_method<D>, nullptr, check_mpm},
  };
  return table;
}

/// The entry of the case's method (InputError if unknown).
template <int D>
const Entry<D>& entry(const CaseSpec& spec) {
  check_method(spec);
  return *std::find_if(entries<D>().begin(), entries<D>().end(), [&](const Entry<D>& e) { return spec.method == e.name; });
}

std::string known_names() {
  std::string out;
  for (const std::string& name : method_names()) out += (out.empty() ? "\"" : ", \"") + name + "\"";
  return out;
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

void check_decomposable(const CaseSpec& spec) {
  const std::string rule = " is not decomposed over MPI ranks yet: run this case as one process (without mpirun)";
  if (spec.method != "sph") throw InputError(spec.file, "/method", "method \"" + spec.method + "\"" + rule);
}

std::vector<std::string> method_names() {
  std::vector<std::string> out;
  for (const Entry<2>& e : entries<2>()) out.push_back(e.name);
  return out;
}

void check_method(const CaseSpec& spec) {
  const std::vector<std::string> known = method_names();
  const auto unknown = [&](const std::string& name) { return std::find(known.begin(), known.end(), name) == known.end(); };
  if (unknown(spec.method))
    throw InputError(spec.file, "/method", "unknown method \"" + spec.method + "\"; this build knows " + known_names());
  for (const auto& [name, params] : spec.methods.items())
    if (unknown(name))
      throw InputError(spec.file, "/methods/" + name, "unknown method \"" + name + "\"; this build knows " + known_names());
  for (const Entry<2>& e : entries<2>())
    if (e.check && spec.supports(e.name)) e.check(spec);
}

CaseSpec with_method(CaseSpec spec, const std::string& name) {
  check_method(spec);
  if (name.empty()) return spec;
  if (!spec.supports(name)) {
    std::string supported = "\"" + spec.method + "\"";
    for (const auto& [other, params] : spec.methods.items()) supported += ", \"" + other + "\"";
    throw InputError(spec.file, "/methods", "--method " + name + ": the case supports only " + supported);
  }
  if (spec.methods.contains(name))  // the method's own parameters are part of what its run depends on
    spec.parameters_hash = parameters_hash(json{{"case", spec.parameters_hash}, {name, spec.methods[name]}});
  spec.method = name;
  return spec;
}

bool method_writes_checkpoints(const std::string& name) {
  for (const Entry<2>& e : entries<2>())
    if (name == e.name) return e.resume != nullptr;
  return false;
}

template <int D>
std::unique_ptr<Method<D>> make_method(const CaseSpec& spec, double dx, bool decompose) {
  const Entry<D>& e = entry<D>(spec);
  if (!decompose) return e.make(spec, dx);
  check_decomposable(spec);
  return make_decomposed_sph_method<D>(spec, dx);
}

template <int D>
std::unique_ptr<Method<D>> resume_method(const CaseSpec& spec, double dx, const std::string& path, json& run,
                                         bool decompose) {
  const Entry<D>& e = entry<D>(spec);
  if (decompose) check_decomposable(spec);
  if (!e.resume)
    throw InputError(spec.file, "/method", "--resume: method \"" + spec.method + "\" writes no checkpoints");
  const Checkpoint c = read_checkpoint(path);
  check_same_run(c, spec, dx);
  run = c.state.run;
  return decompose ? resume_decomposed_sph_method<D>(spec, dx, c) : e.resume(spec, dx, c);
}

template std::unique_ptr<Method<2>> make_method<2>(const CaseSpec&, double, bool);
template std::unique_ptr<Method<3>> make_method<3>(const CaseSpec&, double, bool);
template std::unique_ptr<Method<2>> resume_method<2>(const CaseSpec&, double, const std::string&, json&, bool);
template std::unique_ptr<Method<3>> resume_method<3>(const CaseSpec&, double, const std::string&, json&, bool);

}  // namespace sc
