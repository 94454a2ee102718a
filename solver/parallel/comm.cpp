#include "parallel/comm.hpp"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <stdexcept>

#include "core/errors.hpp"

#ifdef SANDCASTLE_HAS_MPI
#include <mpi.h>
#endif

namespace sc {

namespace {

#ifdef SANDCASTLE_HAS_MPI
bool mpi_running() {
  int initialized = 0, finalized = 0;
  MPI_Initialized(&initialized);
  MPI_Finalized(&finalized);
  return initialized && !finalized;
}

/// Byte counts as MPI's int counts (a message of 2 GiB or more is refused, not truncated).
int count_of(std::size_t bytes) {
  if (bytes > static_cast<std::size_t>(INT32_MAX)) throw std::runtime_error("MPI message of 2 GiB or more");
  return static_cast<int>(bytes);
}

/// Offsets of consecutive blocks of the given sizes, and their total.
std::vector<int> offsets_of(const std::vector<int>& sizes, std::size_t& total) {
  std::vector<int> offsets(sizes.size(), 0);
  std::size_t at = 0;
  for (std::size_t r = 0; r < sizes.size(); ++r) {
    offsets[r] = count_of(at);
    at += static_cast<std::size_t>(sizes[r]);
  }
  total = at;
  count_of(total);
  return offsets;
}

std::vector<std::string> split(const std::string& all, const std::vector<int>& sizes, const std::vector<int>& offsets) {
  std::vector<std::string> out(sizes.size());
  for (std::size_t r = 0; r < sizes.size(); ++r) out[r] = all.substr(static_cast<std::size_t>(offsets[r]), static_cast<std::size_t>(sizes[r]));
  return out;
}
#endif

/// The kind and message of an error, as "<kind digit><message>".
std::string describe(std::exception_ptr error) {
  try {
    std::rethrow_exception(error);
  } catch (const InputError& e) {
    return std::to_string(static_cast<int>(RankError::Kind::Input)) + e.what();
  } catch (const BlowUpError& e) {
    return std::to_string(static_cast<int>(RankError::Kind::BlowUp)) + e.what();
  } catch (const std::exception& e) {
    return std::to_string(static_cast<int>(RankError::Kind::Other)) + e.what();
  } catch (...) {
    return std::to_string(static_cast<int>(RankError::Kind::Other)) + "unknown error";
  }
}

}  // namespace

Comm Comm::world() {
  Comm c;
#ifdef SANDCASTLE_HAS_MPI
  if (mpi_running()) {
    MPI_Comm_rank(MPI_COMM_WORLD, &c.rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &c.size_);
  }
#endif
  return c;
}

void Comm::min(std::span<double> values) const {
#ifdef SANDCASTLE_HAS_MPI
  if (size_ > 1) MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
#else
  (void)values;
#endif
}

void Comm::max(std::span<double> values) const {
#ifdef SANDCASTLE_HAS_MPI
  if (size_ > 1) MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
#else
  (void)values;
#endif
}

void Comm::min(std::span<std::uint64_t> values) const {
#ifdef SANDCASTLE_HAS_MPI
  if (size_ > 1)
    MPI_Allreduce(MPI_IN_PLACE, values.data(), count_of(values.size()), MPI_UINT64_T, MPI_MIN, MPI_COMM_WORLD);
#else
  (void)values;
#endif
}

void Comm::sum(std::span<std::uint64_t> values) const {
#ifdef SANDCASTLE_HAS_MPI
  if (size_ > 1)
    MPI_Allreduce(MPI_IN_PLACE, values.data(), count_of(values.size()), MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
#else
  (void)values;
#endif
}

void Comm::sum_below(std::span<std::uint64_t> values) const {
#ifdef SANDCASTLE_HAS_MPI
  if (size_ > 1) {
    std::vector<std::uint64_t> mine(values.begin(), values.end());
    MPI_Exscan(mine.data(), values.data(), count_of(values.size()), MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
  }
#endif
  if (rank_ == 0) std::fill(values.begin(), values.end(), std::uint64_t{0});  // MPI leaves rank 0's undefined
}

std::vector<std::string> Comm::exchange(const std::vector<std::string>& send) const {
  if (send.size() != static_cast<std::size_t>(size_)) throw std::logic_error("Comm::exchange: one message per rank");
#ifdef SANDCASTLE_HAS_MPI
  if (size_ > 1) {
    std::vector<int> send_sizes(send.size()), recv_sizes(send.size());
    for (std::size_t r = 0; r < send.size(); ++r) send_sizes[r] = count_of(send[r].size());
    MPI_Alltoall(send_sizes.data(), 1, MPI_INT, recv_sizes.data(), 1, MPI_INT, MPI_COMM_WORLD);
    std::size_t send_total = 0, recv_total = 0;
    const std::vector<int> send_offsets = offsets_of(send_sizes, send_total), recv_offsets = offsets_of(recv_sizes, recv_total);
    std::string out_bytes;
    out_bytes.reserve(send_total);
    for (const std::string& s : send) out_bytes += s;
    std::string in_bytes(recv_total, '\0');
    MPI_Alltoallv(out_bytes.data(), send_sizes.data(), send_offsets.data(), MPI_BYTE, in_bytes.data(), recv_sizes.data(),
                  recv_offsets.data(), MPI_BYTE, MPI_COMM_WORLD);
    return split(in_bytes, recv_sizes, recv_offsets);
  }
#endif
  return send;
}

std::vector<std::string> Comm::all_gather(const std::string& mine) const {
#ifdef SANDCASTLE_HAS_MPI
  if (size_ > 1) {
    const int size = count_of(mine.size());
    std::vector<int> sizes(static_cast<std::size_t>(size_));
    MPI_Allgather(&size, 1, MPI_INT, sizes.data(), 1, MPI_INT, MPI_COMM_WORLD);
    std::size_t total = 0;
    const std::vector<int> offsets = offsets_of(sizes, total);
    std::string all(total, '\0');
    MPI_Allgatherv(mine.data(), size, MPI_BYTE, all.data(), sizes.data(), offsets.data(), MPI_BYTE, MPI_COMM_WORLD);
    return split(all, sizes, offsets);
  }
#endif
  return {mine};
}

std::string Comm::broadcast(std::string text, int root) const {
#ifdef SANDCASTLE_HAS_MPI
  if (size_ > 1) {
    std::uint64_t size = text.size();
    MPI_Bcast(&size, 1, MPI_UINT64_T, root, MPI_COMM_WORLD);
    text.resize(size);
    MPI_Bcast(text.data(), count_of(size), MPI_BYTE, root, MPI_COMM_WORLD);
  }
#else
  (void)root;
#endif
  return text;
}

void Comm::agree(std::exception_ptr error) const {
  std::array<std::uint64_t, 1> failed = {error ? static_cast<std::uint64_t>(rank_) : UINT64_MAX};
  min(failed);
  if (failed[0] == UINT64_MAX) return;
  const int root = static_cast<int>(failed[0]);
  const std::string what = broadcast(rank_ == root ? describe(error) : std::string(), root);
  throw RankError(root, static_cast<RankError::Kind>(what.at(0) - '0'), what.substr(1));
}

void Comm::abort(int code) const {
#ifdef SANDCASTLE_HAS_MPI
  if (size_ > 1) MPI_Abort(MPI_COMM_WORLD, code);
#endif
  std::exit(code);
}

}  // namespace sc
