// The ranks of an MPI run as the solver sees them: the few collectives the domain decomposition
// needs (parallel/decomposition.hpp), each with a result that does not depend on timing or on the
// order in which ranks arrive. Minima and maxima are exact in any order; sums are of integers only;
// everything else moves bytes. Without MPI (a build without it, or a process not started by a
// launcher) there is one rank and every collective is the identity.
#pragma once
#include <cstdint>
#include <exception>
#include <span>
#include <string>
#include <vector>

namespace sc {

class Comm {
 public:
  /// Every rank of the run (MPI_COMM_WORLD while MPI is initialised; else one rank).
  static Comm world();
  int rank() const { return rank_; }
  int size() const { return size_; }

  /// Element-wise minimum and maximum over the ranks, in place.
  void min(std::span<double> values) const;
  void max(std::span<double> values) const;
  void min(std::span<std::uint64_t> values) const;
  /// Element-wise sum over the ranks, in place (integers: exact in any order).
  void sum(std::span<std::uint64_t> values) const;
  /// Element-wise sum over the ranks below this one, in place (rank 0: zeros; integers: exact).
  void sum_below(std::span<std::uint64_t> values) const;
  /// Sends send[r] to rank r and returns what each rank sent to this one, by source rank.
  std::vector<std::string> exchange(const std::vector<std::string>& send) const;
  /// Every rank's `mine`, by rank, on every rank.
  std::vector<std::string> all_gather(const std::string& mine) const;
  /// Rank `root`'s `text` on every rank.
  std::string broadcast(std::string text, int root) const;
  /// Whether every rank got through: `error` is this rank's error (null if none). If any rank has
  /// one, throws on every rank the RankError (core/errors.hpp) of the lowest such rank's. Collective.
  void agree(std::exception_ptr error) const;
  /// Ends every rank of the run at once with exit code `code` (MPI_Abort; std::exit in one rank):
  /// the last resort for an error on one rank in the middle of a collective exchange.
  [[noreturn]] void abort(int code) const;

 private:
  int rank_ = 0, size_ = 1;
};

/// Runs `local` on every rank of `comm` and ends it alike on all (Comm::agree): an error on one rank
/// is thrown on every rank as a RankError. The collectives `local` calls, if any, must all come
/// before whatever may fail on one rank only (e.g. the gather of the state, then rank 0's write).
template <class F>
void run_agreed(const Comm& comm, F&& local) {
  if (comm.size() == 1) return local();
  std::exception_ptr error;
  try {
    local();
  } catch (...) {
    error = std::current_exception();
  }
  comm.agree(error);
}

}  // namespace sc
