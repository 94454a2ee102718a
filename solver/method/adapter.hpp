// What the adapters of the methods other than SPH (FLIP, DEM, MPM) share behind the method seam:
// the base ParticleAdapter (the last good state, the checksum, the frames, no checkpoints), their
// stage times, the reading of a method's own "methods" entry and the scene limits they share, and the
// factories' check that every block lies inside a grid. Each adapter keeps in its own folder only
// what is specific to its method.
#pragma once
#include <array>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "case/case_file.hpp"
#include "core/checksum.hpp"
#include "core/errors.hpp"
#include "core/stage_timers.hpp"
#include "method/method.hpp"
#include "method/view_vtu.hpp"

namespace sc {

/// A method whose state is one container of particles (positions x, velocities v, size()) that it
/// copies at the start of every step, so that a blow-up can show the state before the failed step.
/// It answers what FLIP, DEM and MPM answer the same way: the checksum of that container in storage
/// order, its frames, and no checkpoints (none of them resumes bitwise yet). The adapter names its
/// state (state()) and how particles are seen (view_of()), and calls keep_last_good() before it
/// changes the state.
template <int D, class State>
class ParticleAdapter : public Method<D> {
 public:
  std::string checksum() const override {
    const ParticleView<D> now = motion(state());
    return state_checksum<D>(now.x, now.v);
  }
  std::string vtu_frame() const override { return vtu_document<D>(this->particles()); }
  std::string last_good_frame() const override { return vtu_document<D>(view_of(last_good_)); }
  bool writes_checkpoints() const override { return false; }
  /// Never called (writes_checkpoints() is false); throws std::logic_error.
  void write_checkpoint(const std::string&, const json&) const override {
    throw std::logic_error("method \"" + std::string(this->name()) + "\" writes no checkpoints");
  }

 protected:
  /// `initial`: the state at t = 0, the last good one until the first step.
  explicit ParticleAdapter(State initial) : last_good_(std::move(initial)) {}
  /// Copies the current state as the last good one (at the start of a step).
  void keep_last_good() { last_good_ = state(); }
  /// The view of particles `s` with their positions and velocities only, which view_of() completes.
  static ParticleView<D> motion(const State& s) {
    ParticleView<D> view;
    view.x = {s.x.data(), s.size()};
    view.v = {s.v.data(), s.size()};
    return view;
  }

 private:
  /// The particles the method moves now.
  virtual const State& state() const = 0;
  /// Particles `s` (the current ones or the last good ones) as the view of the method's fields.
  virtual ParticleView<D> view_of(const State& s) const = 0;

  State last_good_;
};

/// The stage times of a method timed by `clock`, in the order of `names`, with `count` work units
/// on the stage `counted` and none counted on the others (StageTime).
template <class Stage, std::size_t N>
std::vector<StageTime> stage_times_of(const std::array<std::string_view, N>& names, const StageClock<Stage>& clock,
                                      Stage counted, long count) {
  std::vector<StageTime> out;
  for (std::size_t s = 0; s < N; ++s) {
    const auto stage = static_cast<Stage>(s);
    out.push_back({std::string(names[s]), clock.seconds(stage), stage == counted ? count : 0});
  }
  return out;
}

/// The case's "methods"/<method> object of the method's own parameters (empty when the case names
/// the method without one), for a JsonObject rooted at /methods/<method>. Throws InputError when it
/// is not an object; `label` names the method in the message ("FLIP").
inline json own_parameters(const CaseSpec& spec, const std::string& method, const std::string& label) {
  const json own = spec.methods.contains(method) ? spec.methods.at(method) : json::object();
  if (!own.is_object()) throw InputError(spec.file, "/methods/" + method, "must be an object of " + label + "'s parameters");
  return own;
}

/// Throws InputError (the case file, the JSON path, the rule) for a scene that none of FLIP, DEM and
/// MPM runs: no tank (`tank_role`: what its sides are to the method), meshes, a porous section
/// (`porous_rule`: why the method reads none; empty for a method that reads it), or split and merge.
inline void check_tank_scene(const CaseSpec& spec, const std::string& method, const std::string& tank_role,
                             const std::string& porous_rule) {
  const std::string name = "method \"" + method + "\" ";
  if (!spec.tank) throw InputError(spec.file, "/tank", name + "needs a tank (" + tank_role + ")");
  if (!spec.meshes.empty()) throw InputError(spec.file, "/meshes", name + "fills blocks only, not meshes");
  if (spec.porous && !porous_rule.empty()) throw InputError(spec.file, "/porous", name + porous_rule);
  if (spec.adaptive) throw InputError(spec.file, "/adaptive", name + "has no split and merge");
}

/// Throws InputError (the case file, /blocks/<b>, the rule) for the first of the case's blocks that
/// reaches outside [lo, hi], the box of `where` (a grid method seeds particles only on its grid).
template <int D>
void check_blocks_inside(const CaseSpec& spec, std::string_view method, std::string_view where, const Vec<D>& lo,
                         const Vec<D>& hi) {
  for (std::size_t b = 0; b < spec.blocks.size(); ++b)
    for (int d = 0; d < D; ++d)
      if (spec.blocks[b].min[d] < lo[d] || spec.blocks[b].max[d] > hi[d])
        throw InputError(spec.file, "/blocks/" + std::to_string(b),
                         "method \"" + std::string(method) + "\": the block must lie inside " + std::string(where) +
                             " (the tank, open sides to the domain)");
}

}  // namespace sc
