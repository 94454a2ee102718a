// Cheap per-stage wall-clock timers, kept in every run so any run can report where its time goes.
#pragma once
#include <array>
#include <chrono>
#include <cstddef>
#include <optional>
#include <string_view>

namespace sc {

/// Halo: the domain decomposition's exchanges between MPI ranks (parallel/decomposition.hpp): the
/// global grid, migration, the halo and its refreshes, and the step size's reduction.
enum class Stage { Neighbours, Porous, Density, Forces, Clusters, Adaptive, Integration, Output, Halo, Count };

inline constexpr std::array<std::string_view, static_cast<std::size_t>(Stage::Count)> stage_names = {
    "neighbours", "porous", "density", "forces", "clusters", "adaptive", "integration", "output", "halo"};

/// Exclusive stage times: every instant counts in exactly one stage. A scope opened inside another
/// one pauses the outer stage until it closes, so nested scopes never count twice and an outer
/// scope collects whatever its inner scopes leave untimed. `S` is a method's enum of stages,
/// `S::Count` their number.
template <class S>
class StageClock {
  static constexpr std::size_t count = static_cast<std::size_t>(S::Count);

 public:
  using Clock = std::chrono::steady_clock;
  /// Times the enclosing scope and adds it to `stage` (minus the scopes opened inside it).
  class Scope {
   public:
    Scope(StageClock& t, S s) : t_(t), outer_(t.active_) { t_.switch_to(s); }
    ~Scope() { t_.switch_to(outer_); }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    StageClock& t_;
    std::optional<S> outer_;
  };
  Scope time(S s) { return Scope(*this, s); }
  double seconds(S s) const { return seconds_[static_cast<std::size_t>(s)]; }
  void reset() { seconds_.fill(0.0); }

 private:
  /// Charges the time since the last switch to the active stage, then makes `s` the active one.
  void switch_to(std::optional<S> s) {
    const Clock::time_point now = Clock::now();
    if (active_) seconds_[static_cast<std::size_t>(*active_)] += std::chrono::duration<double>(now - since_).count();
    active_ = s;
    since_ = now;
  }

  std::array<double, count> seconds_{};
  std::optional<S> active_;
  Clock::time_point since_{};
};

/// The stage times of SPH (solver/simulator/).
using StageTimers = StageClock<Stage>;

}  // namespace sc
