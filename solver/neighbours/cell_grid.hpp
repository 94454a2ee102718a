// Uniform cell grid over bare points (positions only), for gather loops outside the SPH particle
// set: the DEM contacts and wetness, and the observers that count neighbours of any method's
// particles. Points are sorted into cells once (a serial counting sort, so the order is fixed), and a
// query visits the 3^D cells around a position in cell order, each cell's points in index order.
// A point that sums over its neighbours in this order gets bitwise the same result for any number
// of threads.
#pragma once
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <vector>

#include "core/types.hpp"

namespace sc {

template <int D>
class CellGrid {
 public:
  /// Sorts `x` into cells of size `cell` (at least the largest interaction range).
  void build(std::span<const Vec<D>> x, double cell) {
    if (!(cell > 0.0)) throw std::invalid_argument("CellGrid: cell size must be positive");
    cell_ = cell;
    Vec<D> lo = Vec<D>::Constant(INFINITY), hi = Vec<D>::Constant(-INFINITY);
    for (const auto& p : x) { lo = lo.cwiseMin(p); hi = hi.cwiseMax(p); }
    if (x.empty()) lo = hi = Vec<D>::Zero();
    lo_ = lo;
    std::int64_t cells = 1;
    for (int d = 0; d < D; ++d) {
      dims_[d] = static_cast<std::int64_t>(std::floor((hi[d] - lo[d]) / cell)) + 1;
      cells *= dims_[d];
    }
    start_.assign(static_cast<std::size_t>(cells) + 1, 0);
    cell_of_.resize(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
      cell_of_[i] = linear(coords(x[i]));
      ++start_[cell_of_[i] + 1];
    }
    for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    sorted_.resize(x.size());
    std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < x.size(); ++i) sorted_[fill[cell_of_[i]]++] = static_cast<std::uint32_t>(i);
  }

  /// Calls f(j) for every point j in the (2 rings + 1)^D cells around position p (a superset of
  /// the points within `rings` cell sizes of p), in a fixed order.
  template <class F>
  void for_each_near(const Vec<D>& p, F&& f, int rings = 1) const {
    std::array<std::int64_t, D> c, from, to;
    for (int d = 0; d < D; ++d) {
      c[d] = static_cast<std::int64_t>(std::floor((p[d] - lo_[d]) / cell_));
      from[d] = std::max<std::int64_t>(c[d] - rings, 0);
      to[d] = std::min<std::int64_t>(c[d] + rings, dims_[d] - 1);
      if (from[d] > to[d]) return;
    }
    std::array<std::int64_t, D> k = from;
    while (true) {
      std::int64_t lin = 0;
      for (int d = D - 1; d >= 0; --d) lin = lin * dims_[d] + k[d];
      for (auto s = start_[lin]; s < start_[lin + 1]; ++s) f(sorted_[s]);
      int d = 0;
      while (d < D && ++k[d] > to[d]) { k[d] = from[d]; ++d; }
      if (d == D) return;
    }
  }

 private:
  std::array<std::int64_t, D> coords(const Vec<D>& p) const {
    std::array<std::int64_t, D> c;
    for (int d = 0; d < D; ++d) c[d] = std::min(static_cast<std::int64_t>(std::floor((p[d] - lo_[d]) / cell_)), dims_[d] - 1);
    return c;
  }
  std::size_t linear(const std::array<std::int64_t, D>& c) const {
    std::int64_t lin = 0;
    for (int d = D - 1; d >= 0; --d) lin = lin * dims_[d] + c[d];
    return static_cast<std::size_t>(lin);
  }

  double cell_ = 1.0;
  Vec<D> lo_ = Vec<D>::Zero();
  std::array<std::int64_t, D> dims_{};
  std::vector<std::uint32_t> start_, cell_of_, sorted_;
};

}  // namespace sc
