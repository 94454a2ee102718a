// Sweeps of independent runs over MPI ranks (docs/architecture.md, "Sweeps over ranks").
//
// One binary runs alone or under `mpirun`: MpiSession starts MPI only when a launcher started the
// process (OpenMPI's or a PMI/PMIx environment), so a plain `sandcastle validate` never touches
// MPI, and a build without MPI (SANDCASTLE_MPI off, or OpenMPI not found) runs every sweep in the
// one process. Under `mpirun -n N`, sweep() hands the tasks out longest expected first, each to
// the next rank that is free (a shared counter in an MPI window on rank 0, advanced by an atomic
// fetch-and-add, so every rank, rank 0 too, works), and gathers the results on rank 0 in task
// order: what rank 0 reports does not depend on the rank count or on which rank ran what.
#pragma once
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace sc {

/// MPI for the lifetime of main(): MPI_Init_thread (funneled: only the main thread calls MPI) when
/// a launcher started the process, MPI_Finalize at the end. At most one per process.
class MpiSession {
 public:
  MpiSession(int& argc, char**& argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
};

/// This process's rank and the number of ranks (0 and 1 without MPI).
int sweep_rank();
int sweep_ranks();
/// The build has MPI (independent of whether this process runs under mpirun).
bool sweep_has_mpi();

/// Runs task(i) for i = 0 .. cost.size() − 1, each exactly once on some rank, and returns every
/// result, in index order, on rank 0; other ranks get an empty vector. Under MPI the tasks of larger
/// cost[i] start first (ties in index order); in one process they run in index order. `progress`,
/// if given, is called on rank 0 with the results known there so far (index order, "" for a task
/// not yet known) each time one more is known: after each task in one process, after each of rank
/// 0's own tasks under MPI. A task must not throw: it reports its own failure in its result.
using SweepProgress = std::function<void(const std::vector<std::string>&)>;
std::vector<std::string> sweep(const std::vector<double>& cost, const std::function<std::string(std::size_t)>& task,
                               const SweepProgress& progress = {});

/// Rank 0's value of `value` on every rank (identity with one rank).
int broadcast_from_root(int value);

}  // namespace sc
