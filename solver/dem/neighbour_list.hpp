// Verlet neighbour list of the DEM contact step: for each grain, the other grains that lay within
// the interaction range plus a skin when the list was built, in the cell grid's fixed visiting order.
// Every pair within the range stays listed as long as no grain has moved more than half the skin
// since, so the list is rebuilt only then (or when the range grows), not every contact step. Each
// listed pair {i, j} is also numbered once, as a pair of its lower grain i (the pair pass of
// solver/dem/dem_forces.cpp evaluates it there, and both grains gather its result). The order is
// fixed and each grain's entries are written by one thread, so 1 and 2 threads give bitwise the same
// lists.
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
    number_pairs();
  }

  /// Calls f(j) for every grain j listed near grain i, in the fixed order.
  template <class F>
  void for_each_near(std::size_t i, F&& f) const {
    for (std::uint32_t k = start_[i]; k < start_[i + 1]; ++k) f(near_[k]);
  }

  /// Calls f(pair, lower) for every grain j listed near grain i, in the same order, with the number
  /// of the pair {i, j} and whether i is its lower grain (j > i).
  template <class F>
  void for_each_pair(std::size_t i, F&& f) const {
    for (std::uint32_t k = start_[i]; k < start_[i + 1]; ++k) f(pair_[k] >> 1, (pair_[k] & 1u) == 0);
  }

  /// Calls f(j, pair) for every grain j > i listed near grain i (the pairs numbered as i's), in the
  /// fixed order; their numbers run from 0 over the grains in index order.
  template <class F>
  void for_each_owned(std::size_t i, F&& f) const {
    for (std::uint32_t q = owned_start_[i]; q < owned_start_[i + 1]; ++q) f(owned_[q], q);
  }

  /// Number of listed pairs {i, j}, each counted once.
  std::size_t pairs() const { return owned_.size(); }

 private:
  /// Numbers every listed pair {i, j} once, as a pair of its lower grain i: i's pairs (owned_) in the
  /// order of i's list, after those of the grains before i; then gives each entry of the full list
  /// its pair's number, times two plus one where i is the higher grain. The list is symmetric (the
  /// cells and the distance test are), so grain i is in the owned pairs of every grain j < i it lists.
  void number_pairs() {
    const std::size_t n = start_.size() - 1;
    const auto grains = static_cast<std::ptrdiff_t>(n);
    owned_start_.assign(n + 1, 0);
#pragma omp parallel for schedule(dynamic, 256)
    for (std::ptrdiff_t s = 0; s < grains; ++s) {
      const auto i = static_cast<std::size_t>(s);
      owned_start_[i + 1] = static_cast<std::uint32_t>(std::count_if(
          near_.begin() + start_[i], near_.begin() + start_[i + 1], [&](std::uint32_t j) { return j > i; }));
    }
    for (std::size_t i = 0; i < n; ++i) owned_start_[i + 1] += owned_start_[i];
    owned_.resize(owned_start_.back());
    pair_.resize(near_.size());
#pragma omp parallel for schedule(dynamic, 256)
    for (std::ptrdiff_t s = 0; s < grains; ++s) {
      const auto i = static_cast<std::size_t>(s);
      std::uint32_t q = owned_start_[i];
      for (std::uint32_t k = start_[i]; k < start_[i + 1]; ++k)
        if (near_[k] > i) {
          owned_[q] = near_[k];
          pair_[k] = 2 * q++;
        }
    }
#pragma omp parallel for schedule(dynamic, 256)
    for (std::ptrdiff_t s = 0; s < grains; ++s) {
      const auto i = static_cast<std::uint32_t>(s);
      for (std::uint32_t k = start_[i]; k < start_[i + 1]; ++k)
        if (const std::uint32_t j = near_[k]; j < i)
          pair_[k] = 2 * static_cast<std::uint32_t>(std::find(owned_.begin() + owned_start_[j],
                                                              owned_.begin() + owned_start_[j + 1], i) -
                                                    owned_.begin()) + 1;
    }
  }

  template <class F>
  void visit_near(std::span<const Vec<D>> x, std::size_t i, double reach, F&& f) const {
    cells_.for_each_near(x[i], [&](std::uint32_t j) {
      if (j != i && (x[j] - x[i]).squaredNorm() < reach * reach) f(j);
    });
  }

  CellGrid<D> cells_;
  std::vector<Vec<D>, Eigen::aligned_allocator<Vec<D>>> built_at_;
  std::vector<std::uint32_t> start_, near_;  // the full list: grain i's neighbours are near_[start_[i], start_[i + 1])
  std::vector<std::uint32_t> pair_;          // per entry of near_: 2 × its pair's number, + 1 from the higher grain
  std::vector<std::uint32_t> owned_start_, owned_;  // the pairs numbered as i's: owned_[owned_start_[i], owned_start_[i + 1])
  double range_ = 0.0, skin_ = 0.0;
};

}  // namespace sc::dem
