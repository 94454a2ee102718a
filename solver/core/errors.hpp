// Error types with the information the command line needs to pick an exit code and tell the user
// what to fix: bad input (exit 2) names the file, the JSON path and the rule; a blow-up (exit 3)
// names the step, time, particle and field; an error on one rank of a run over MPI ranks is made
// known to every rank, naming the rank (RankError).
#pragma once
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

/// The simulation diverged (NaN/Inf, a particle left the domain, density out of its window).
/// Exit code 3; the caller keeps the last good state.
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
