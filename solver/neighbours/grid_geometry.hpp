// The geometry of the neighbour search's uniform grid: its corner, cell size and cells per axis,
// from the bounds of the particles. One home for the cell of a position, shared by the neighbour
// grid (neighbour_grid.hpp) and the domain decomposition (parallel/decomposition.hpp), which must
// put every particle in the same cell as the grid does on any number of ranks.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "core/types.hpp"

namespace sc {

/// Bounds of a set of particles: the box of their positions and their largest support radius.
/// Exact under min and max, so the bounds of several sets (threads, ranks) combine in any order.
template <int D>
struct GridBounds {
  std::array<double, D> lo, hi;
  double hmax = 0.0;

  /// The empty set's bounds, the identity of merge().
  static GridBounds empty() {
    GridBounds b;
    b.lo.fill(INFINITY);
    b.hi.fill(-INFINITY);
    return b;
  }
  void merge(const GridBounds& o) {
    for (int d = 0; d < D; ++d) {
      lo[d] = std::min(lo[d], o.lo[d]);
      hi[d] = std::max(hi[d], o.hi[d]);
    }
    hmax = std::max(hmax, o.hmax);
  }
};

/// Cells of size hmax from the lowest corner of the bounds, enough of them along each axis to hold
/// the highest position (the last cell also takes what rounding would put beyond it).
template <int D>
struct GridGeometry {
  Vec<D> lo = Vec<D>::Zero();
  double cell = 0.0;
  std::array<std::int64_t, D> dims{};
  std::int64_t cells = 0;

  static GridGeometry from_bounds(const GridBounds<D>& b) {
    if (!(b.hmax > 0.0)) throw std::logic_error("neighbour search: support radius must be positive");
    GridGeometry g;
    g.cell = b.hmax;
    g.cells = 1;
    for (int d = 0; d < D; ++d) {
      g.lo[d] = b.lo[d];
      g.dims[d] = static_cast<std::int64_t>(std::floor((b.hi[d] - b.lo[d]) / b.hmax)) + 1;
      g.cells *= g.dims[d];
    }
    if (g.cells > 400'000'000) throw std::runtime_error("neighbour search: particles spread over too many cells");
    return g;
  }
  /// The cell coordinate of position x along axis d.
  std::int64_t coord(const Vec<D>& x, int d) const {
    return std::min<std::int64_t>(dims[d] - 1, static_cast<std::int64_t>((x[d] - lo[d]) / cell));
  }
  /// The linear index of x's cell (x fastest).
  std::int64_t cell_of(const Vec<D>& x) const {
    std::int64_t c = 0;
    for (int d = D - 1; d >= 0; --d) c = c * dims[d] + coord(x, d);
    return c;
  }
  bool operator==(const GridGeometry&) const = default;
};

}  // namespace sc
