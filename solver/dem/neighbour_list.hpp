// Verlet neighbour list of the DEM contact gather: for each grain, the other grains that lay within
// the interaction range plus a skin when the list was built, in the cell grid's fixed visiting order.
// Every pair within the range stays listed as long as no grain has moved more than half the skin
// since, so the list is rebuilt only then (or when the range grows), not every contact step. The
// order is fixed and each grain's list is written by one thread, so 1 and 2 threads give bitwise the
// same lists.
#pragma once
#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "neighbours/cell_grid.hpp"

namespace sc::dem {

template <int D>
class NeighbourList {
 public:
  /// Whether the list must be built again for positions x and interaction range `range`.
  bool stale(std::span<const Vec<D>> x, double range) const {
    if (x.size() != built_at_.size() || range > range_) return true;
    double moved = 0.0;
    const auto n = static_cast<std::ptrdiff_t>(x.size());
#pragma omp parallel for schedule(static) reduction(max : moved)  // exact: any threads
    for (std::ptrdiff_t i = 0; i < n; ++i) moved = std::max(moved, (x[i] - built_at_[i]).squaredNorm());
    return 4.0 * moved > skin_ * skin_;
  }

  /// Lists, for every point, the others within range + skin of it.
  void build(std::span<const Vec<D>> x, double range, double skin) {
    range_ = range;
    skin_ = skin;
    const double reach = range + skin;
    cells_.build(x, reach);
    built_at_.assign(x.begin(), x.end());
    const auto n = static_cast<std::ptrdiff_t>(x.size());
    std::vector<std::uint32_t> count(x.size() + 1, 0);
#pragma omp parallel for schedule(dynamic, 256)  // grains in dense regions have more neighbours
    for (std::ptrdiff_t s = 0; s < n; ++s) {
      std::uint32_t c = 0;
      visit_near(x, static_cast<std::size_t>(s), reach, [&](std::uint32_t) { ++c; });
      count[static_cast<std::size_t>(s) + 1] = c;
    }
    for (std::size_t i = 0; i < x.size(); ++i) count[i + 1] += count[i];
    start_ = std::move(count);
    near_.resize(start_.back());
#pragma omp parallel for schedule(dynamic, 256)  // grains in dense regions have more neighbours
    for (std::ptrdiff_t s = 0; s < n; ++s) {
      std::uint32_t k = start_[static_cast<std::size_t>(s)];
      visit_near(x, static_cast<std::size_t>(s), reach, [&](std::uint32_t j) { near_[k++] = j; });
    }
  }

  /// Calls f(j) for every grain j listed near grain i, in the fixed order.
  template <class F>
  void for_each_near(std::size_t i, F&& f) const {
    for (std::uint32_t k = start_[i]; k < start_[i + 1]; ++k) f(near_[k]);
  }

 private:
  template <class F>
  void visit_near(std::span<const Vec<D>> x, std::size_t i, double reach, F&& f) const {
    cells_.for_each_near(x[i], [&](std::uint32_t j) {
      if (j != i && (x[j] - x[i]).squaredNorm() < reach * reach) f(j);
    });
  }

  CellGrid<D> cells_;
  std::vector<Vec<D>, Eigen::aligned_allocator<Vec<D>>> built_at_;
  std::vector<std::uint32_t> start_, near_;
  double range_ = 0.0, skin_ = 0.0;
};

}  // namespace sc::dem
