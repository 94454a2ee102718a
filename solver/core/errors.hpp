// Error types with the information the command line needs to pick an exit code and tell the user
// what to fix: bad input (exit 2) names the file, the JSON path and the rule; a blow-up (exit 3)
// names the step, time, particle and field; an error on one rank of a run over MPI ranks is made
// known to every rank, naming the rank (RankError).
#pragma once
#include <cstdio>
#include <stdexcept>
#include <string>

namespace sc {

/// Bad user input: a malformed case file, an out-of-range value, a missing file. Exit code 2.
class InputError : public std::runtime_error {
 public:
  InputError(std::string file, std::string json_path, std::string rule)
      : std::runtime_error(file + ": " + (json_path.empty() ? std::string("(document)") : json_path) +
                           ": " + rule),
        file_(std::move(file)), path_(std::move(json_path)), rule_(std::move(rule)) {}
  const std::string& file() const { return file_; }
  const std::string& json_path() const { return path_; }
  const std::string& rule() const { return rule_; }

 private:
  std::string file_, path_, rule_;
};

/// The simulation diverged (NaN/Inf, a particle left the domain, density out of its window, a step
/// shrunk without end). Exit code 3; the caller keeps the last good state. `step` is the step that
/// failed, counted from 1: the last good state is the one after step − 1.
class BlowUpError : public std::runtime_error {
 public:
  BlowUpError(long step, double time, long particle, std::string phase, std::string field, std::string what)
      : std::runtime_error("blow-up at step " + std::to_string(step) + ", t = " + std::to_string(time) +
                           " s, particle " + std::to_string(particle) + " (" + phase + "), field '" + field +
                           "': " + what),
        step_(step), particle_(particle) {}
  long step() const { return step_; }
  long particle() const { return particle_; }

 private:
  long step_, particle_;
};

/// The shortest step, as a fraction of the case's step, that a method whose step follows a CFL
/// condition (MPM's substeps, FLIP's and SPH's steps) may take. Speeds running away shrink such a
/// step without end, and the run would stall, or overflow its count of substeps, instead of stopping.
inline constexpr double kShortestStepFraction = 1e-4;

/// Why a step collapsed: "<cause> of <value> <unit> shrinks the stable step to <stable> s, below
/// kShortestStepFraction of the case's step (<nominal> s)", e.g. cause "a speed", unit "m/s".
inline std::string collapsed_step_reason(const char* cause, double value, const char* unit, double stable, double nominal) {
  char what[240];
  std::snprintf(what, sizeof what, "%s of %.3g %s shrinks the stable step to %.3g s, below %g of the case's step (%g s)",
                cause, value, unit, stable, kShortestStepFraction, nominal);
  return what;
}

/// The blow-up of a step that the fastest particle's speed shrank to `stable`, below
/// kShortestStepFraction of the case's step `nominal`. `v`: the particles' velocities (vectors with
/// squaredNorm and norm); `is_sand(i)`: whether particle i is sand (the diagnostic's phase).
template <class Velocities, class IsSand>
BlowUpError collapsed_step(long step, double time, const Velocities& v, IsSand is_sand, double stable, double nominal) {
  long fastest = 0;
  for (long i = 1; i < static_cast<long>(v.size()); ++i)
    if (v[i].squaredNorm() > v[fastest].squaredNorm()) fastest = i;
  const double speed = v.empty() ? 0.0 : v[fastest].norm();
  return BlowUpError(step, time, fastest, is_sand(fastest) ? "sand" : "water", "v",
                     collapsed_step_reason("a speed", speed, "m/s", stable, nominal));
}

/// An error on one rank of a run over several MPI ranks, made known to every rank (Comm::agree) so
/// that all of them stop alike: the lowest failing rank, its error's message, and the kind of that
/// error, which picks the exit code as it would in one process.
class RankError : public std::runtime_error {
 public:
  enum class Kind { Input, BlowUp, Other };
  RankError(int rank, Kind kind, const std::string& what)
      : std::runtime_error("rank " + std::to_string(rank) + ": " + what), rank_(rank), kind_(kind) {}
  int rank() const { return rank_; }
  Kind kind() const { return kind_; }

 private:
  int rank_;
  Kind kind_;
};

}  // namespace sc
