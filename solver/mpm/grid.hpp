// The background grid of two-grid MPM and the binning of particles by cell, from which each node
// gathers its particles in a fixed order: no two threads ever add into the same node, so a run is
// bitwise the same on any number of OpenMP threads (docs/equations.md §9).
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <span>
#include <vector>

#include "core/types.hpp"

namespace sc::mpm {

/// A uniform grid of nodes x_i = origin + i h, i in [0, count) along each axis.
template <int D>
struct Grid {
  Vec<D> origin = Vec<D>::Zero();
  double h = 1.0;
  std::array<long, D> count{};

  std::size_t node_count() const {
    std::size_t n = 1;
    for (int d = 0; d < D; ++d) n *= static_cast<std::size_t>(count[d]);
    return n;
  }
  /// The linear index of the node with axis indices `i` (axis 0 fastest).
  std::size_t linear(const std::array<long, D>& i) const {
    std::size_t k = 0;
    for (int d = D - 1; d >= 0; --d) k = k * static_cast<std::size_t>(count[d]) + static_cast<std::size_t>(i[d]);
    return k;
  }
  std::array<long, D> axes(std::size_t k) const {
    std::array<long, D> i{};
    for (int d = 0; d < D; ++d) {
      i[d] = static_cast<long>(k % static_cast<std::size_t>(count[d]));
      k /= static_cast<std::size_t>(count[d]);
    }
    return i;
  }
  Vec<D> position(const std::array<long, D>& i) const {
    Vec<D> x;
    for (int d = 0; d < D; ++d) x[d] = origin[d] + static_cast<double>(i[d]) * h;
    return x;
  }
  /// The lowest of the 3^D nodes a particle at x reaches: floor((x − origin)/h − 1/2) per axis,
  /// clamped to the grid so that the particle's stencil stays inside it.
  std::array<long, D> base(const Vec<D>& x) const {
    std::array<long, D> b{};
    for (int d = 0; d < D; ++d)
      b[d] = std::clamp(static_cast<long>(std::floor((x[d] - origin[d]) / h - 0.5)), 0L, count[d] - 3);
    return b;
  }
};

/// Particles sorted by the base node of their stencil (a counting sort, stable in particle index):
/// the particles whose base node is k are order[start[k]] .. order[start[k + 1] − 1].
struct Bins {
  std::vector<std::size_t> start, order;

  std::span<const std::size_t> of(std::size_t k) const { return {order.data() + start[k], start[k + 1] - start[k]}; }
};

/// Bins the particles `members` (indices into x, in increasing order) by base node.
template <int D>
void bin_particles(const Grid<D>& grid, std::span<const Vec<D>> x, std::span<const std::size_t> members, Bins& bins) {
  const std::size_t n = grid.node_count();
  bins.start.assign(n + 1, 0);
  std::vector<std::size_t> key(members.size());
  for (std::size_t k = 0; k < members.size(); ++k) {
    key[k] = grid.linear(grid.base(x[members[k]]));
    ++bins.start[key[k] + 1];
  }
  for (std::size_t k = 0; k < n; ++k) bins.start[k + 1] += bins.start[k];
  bins.order.resize(members.size());
  std::vector<std::size_t> next(bins.start.begin(), bins.start.end() - 1);
  for (std::size_t k = 0; k < members.size(); ++k) bins.order[next[key[k]]++] = members[k];
}

/// Calls visit(p, offset) for every particle in the bins whose stencil reaches node `i`, `offset`
/// the node's place in the particle's stencil (i − base, 0 to 2 per axis); bins in a fixed order
/// (base nodes i − 2 .. i per axis, axis 0 fastest), each bin in particle order.
template <int D, class Visit>
void for_particles_near(const Grid<D>& grid, const Bins& bins, const std::array<long, D>& i, Visit&& visit) {
  constexpr int stencil = D == 2 ? 9 : 27;
  for (int s = 0; s < stencil; ++s) {
    std::array<long, D> b{};
    std::array<int, D> offset{};
    int rest = s;
    bool inside = true;
    for (int d = 0; d < D; ++d) {
      offset[d] = 2 - rest % 3;
      b[d] = i[d] - offset[d];
      rest /= 3;
      inside = inside && b[d] >= 0 && b[d] <= grid.count[d] - 3;
    }
    if (!inside) continue;
    for (const std::size_t p : bins.of(grid.linear(b))) visit(p, offset);
  }
}

}  // namespace sc::mpm
