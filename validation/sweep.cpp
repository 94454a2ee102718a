#include "sweep.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <numeric>

#ifdef SANDCASTLE_HAS_MPI
#include <mpi.h>
#endif

namespace sc {

namespace {

std::vector<std::string> serial_sweep(std::size_t count, const std::function<std::string(std::size_t)>& task,
                                      const SweepProgress& progress) {
  std::vector<std::string> results(count);
  for (std::size_t i = 0; i < count; ++i) {
    results[i] = task(i);
    if (progress) progress(results);
  }
  return results;
}

#ifdef SANDCASTLE_HAS_MPI
/// The process was started by an MPI launcher (OpenMPI's mpirun, or a PMI/PMIx one such as srun).
bool launched_by_mpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK"})
    if (std::getenv(name)) return true;
  return false;
}

bool mpi_running() {
  int initialized = 0, finalized = 0;
  MPI_Initialized(&initialized);
  MPI_Finalized(&finalized);
  return initialized && !finalized;
}

/// Task indices by decreasing cost, ties in index order.
std::vector<std::size_t> longest_first(const std::vector<double>& cost) {
  std::vector<std::size_t> order(cost.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return cost[a] > cost[b]; });
  return order;
}

/// The next position in the hand-out order: an atomic fetch-and-add on the counter held by rank 0.
long next_position(MPI_Win counter) {
  const long one = 1;
  long got = 0;
  MPI_Win_lock(MPI_LOCK_SHARED, 0, 0, counter);
  MPI_Fetch_and_op(&one, &got, MPI_LONG, 0, 0, MPI_SUM, counter);
  MPI_Win_unlock(0, counter);
  return got;
}

/// A rank's results as one buffer: per result its task index and length (8 bytes each), then its bytes.
std::string pack(const std::vector<std::pair<std::size_t, std::string>>& done) {
  std::string buffer;
  for (const auto& [index, text] : done) {
    const std::uint64_t head[2] = {index, text.size()};
    buffer.append(reinterpret_cast<const char*>(head), sizeof head);
    buffer.append(text);
  }
  return buffer;
}

void unpack(const char* data, std::size_t size, std::vector<std::string>& results) {
  for (std::size_t at = 0; at < size;) {
    std::uint64_t head[2];
    std::memcpy(head, data + at, sizeof head);
    at += sizeof head;
    results.at(head[0]).assign(data + at, head[1]);
    at += head[1];
  }
}

/// Every rank's packed results, concatenated on rank 0 (empty elsewhere).
std::string gather_on_root(const std::string& mine) {
  int ranks = 1, rank = 0;
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const int size = static_cast<int>(mine.size());
  std::vector<int> sizes(static_cast<std::size_t>(ranks)), offsets(static_cast<std::size_t>(ranks), 0);
  MPI_Gather(&size, 1, MPI_INT, sizes.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (rank == 0) std::partial_sum(sizes.begin(), sizes.end() - 1, offsets.begin() + 1);
  std::string all(rank == 0 ? static_cast<std::size_t>(offsets.back() + sizes.back()) : 0, '\0');
  MPI_Gatherv(mine.data(), size, MPI_CHAR, all.data(), sizes.data(), offsets.data(), MPI_CHAR, 0, MPI_COMM_WORLD);
  return all;
}

std::vector<std::string> mpi_sweep(const std::vector<double>& cost, const std::function<std::string(std::size_t)>& task,
                                   const SweepProgress& progress) {
  const std::vector<std::size_t> order = longest_first(cost);
  long* counter_memory = nullptr;
  MPI_Win counter;
  const MPI_Aint bytes = sweep_rank() == 0 ? static_cast<MPI_Aint>(sizeof(long)) : 0;
  MPI_Win_allocate(bytes, sizeof(long), MPI_INFO_NULL, MPI_COMM_WORLD, &counter_memory, &counter);
  if (sweep_rank() == 0) *counter_memory = 0;
  MPI_Barrier(MPI_COMM_WORLD);  // the counter starts at 0 before anyone takes a task
  std::vector<std::pair<std::size_t, std::string>> done;
  std::vector<std::string> known(cost.size());
  for (long k = next_position(counter); k < static_cast<long>(order.size()); k = next_position(counter)) {
    const std::size_t i = order[static_cast<std::size_t>(k)];
    done.emplace_back(i, task(i));
    if (sweep_rank() == 0 && progress) {
      known[i] = done.back().second;
      progress(known);
    }
  }
  MPI_Win_free(&counter);
  const std::string all = gather_on_root(pack(done));
  if (sweep_rank() != 0) return {};
  std::vector<std::string> results(cost.size());
  unpack(all.data(), all.size(), results);
  return results;
}
#endif

}  // namespace

MpiSession::MpiSession(int& argc, char**& argv) {
#ifdef SANDCASTLE_HAS_MPI
  if (!launched_by_mpi()) return;
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
#else
  (void)argc;
  (void)argv;
#endif
}

MpiSession::~MpiSession() {
#ifdef SANDCASTLE_HAS_MPI
  if (mpi_running()) MPI_Finalize();
#endif
}

int sweep_rank() {
  int rank = 0;
#ifdef SANDCASTLE_HAS_MPI
  if (mpi_running()) MPI_Comm_rank(MPI_COMM_WORLD, &rank);
#endif
  return rank;
}

int sweep_ranks() {
  int ranks = 1;
#ifdef SANDCASTLE_HAS_MPI
  if (mpi_running()) MPI_Comm_size(MPI_COMM_WORLD, &ranks);
#endif
  return ranks;
}

bool sweep_has_mpi() {
#ifdef SANDCASTLE_HAS_MPI
  return true;
#else
  return false;
#endif
}

std::vector<std::string> sweep(const std::vector<double>& cost, const std::function<std::string(std::size_t)>& task,
                               const SweepProgress& progress) {
#ifdef SANDCASTLE_HAS_MPI
  if (sweep_ranks() > 1) return mpi_sweep(cost, task, progress);
#endif
  return serial_sweep(cost.size(), task, progress);
}

int broadcast_from_root(int value) {
#ifdef SANDCASTLE_HAS_MPI
  if (sweep_ranks() > 1) MPI_Bcast(&value, 1, MPI_INT, 0, MPI_COMM_WORLD);
#endif
  return value;
}

}  // namespace sc
