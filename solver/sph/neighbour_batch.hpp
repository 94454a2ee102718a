// A particle's neighbours in batches of structure-of-arrays, so that the arithmetic of a pair
// loop vectorises (docs/performance.md, "Pair loops").
//
// A pair loop walks the neighbour list of particle i in batches of up to kSize entries. A batch
// holds, per entry and in list order, the offset d = x_i − x_j (one array per coordinate) and the
// distance r = |d|. The loop then
//   1. gathers the fields it reads of the neighbours into arrays (gather),
//   2. computes its pair terms over the batch into arrays: a loop without branches over
//      contiguous doubles, which the compiler runs two pairs at a time (four with AVX2),
//   3. adds the terms to particle i's sums one entry after another, in list order.
// Each term is the same sequence of IEEE operations as in a loop that takes one pair at a time,
// and the sums are formed in the same order, so the results keep the bits of that loop (tests:
// water/batched_pair_loops_match_one_pair_at_a_time, and the state checksums of the quick tier;
// docs/performance.md on the AVX2 build).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>

#include "core/types.hpp"

namespace sc {

template <int D>
struct NeighbourBatch {
  static constexpr int kSize = 32;
  int size = 0;
  const std::uint32_t* j = nullptr;  // the batch's entries of the list
  alignas(32) double d[D][kSize];    // x_i − x_j per coordinate
  alignas(32) double r[kSize];       // |x_i − x_j|

  /// Copies field[j] of each entry into out[0 .. size).
  template <class T>
  void gather(const T* field, T* out) const {
    for (int k = 0; k < size; ++k) out[k] = field[j[k]];
  }
  /// Whether every value of values[0 .. size) equals v (e.g. all supports equal h_i).
  bool all_equal(const double* values, double v) const {
    return std::all_of(values, values + size, [v](double w) { return w == v; });
  }
};

/// Calls batch_fn(batch) for the list of particle i (at xi) in consecutive batches of up to
/// NeighbourBatch::kSize entries. r is Eigen's norm of d, sqrt((d0² + d1²) + d2²), in that order.
template <int D, class F>
void for_each_batch(std::span<const std::uint32_t> list, const Vec<D>& xi, const Vec<D>* x, F&& batch_fn) {
  NeighbourBatch<D> b;
  for (std::size_t first = 0; first < list.size(); first += NeighbourBatch<D>::kSize) {
    b.size = static_cast<int>(std::min<std::size_t>(NeighbourBatch<D>::kSize, list.size() - first));
    b.j = list.data() + first;
    for (int k = 0; k < b.size; ++k)
      for (int a = 0; a < D; ++a) b.d[a][k] = xi[a] - x[b.j[k]][a];
    for (int k = 0; k < b.size; ++k) {
      double s = b.d[0][k] * b.d[0][k];
      for (int a = 1; a < D; ++a) s += b.d[a][k] * b.d[a][k];
      b.r[k] = std::sqrt(s);
    }
    batch_fn(b);
  }
}

}  // namespace sc
