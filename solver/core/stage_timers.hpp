// Cheap per-stage wall-clock timers, kept in every run so any run can report where its time goes.
#pragma once
#include <array>
#include <chrono>
#include <string_view>

namespace sc {

enum class Stage { Neighbours, Porous, Density, Forces, Clusters, Adaptive, Integration, Output, Count };

inline constexpr std::array<std::string_view, static_cast<std::size_t>(Stage::Count)> stage_names = {
    "neighbours", "porous", "density", "forces", "clusters", "adaptive", "integration", "output"};

class StageTimers {
 public:
  /// Times the enclosing scope and adds it to `stage`.
  class Scope {
   public:
    Scope(StageTimers& t, Stage s) : t_(t), s_(s), start_(std::chrono::steady_clock::now()) {}
    ~Scope() {
      t_.seconds_[static_cast<std::size_t>(s_)] +=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }

   private:
    StageTimers& t_;
    Stage s_;
    std::chrono::steady_clock::time_point start_;
  };
  Scope time(Stage s) { return Scope(*this, s); }
  double seconds(Stage s) const { return seconds_[static_cast<std::size_t>(s)]; }
  void reset() { seconds_.fill(0.0); }

 private:
  std::array<double, static_cast<std::size_t>(Stage::Count)> seconds_{};
};

}  // namespace sc
