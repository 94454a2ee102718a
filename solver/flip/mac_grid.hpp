// Staggered MAC grid of the Zhu & Bridson 2005 PIC/FLIP solver, in 2-D and 3-D.
//
// [Zhu-Bridson 2005: Fluid Simulation Revisited] store pressure and the cell labels at cell centres
// and the velocity component a on the faces normal to axis a. The grid covers the tank box
// [lo, lo + n dx]; the outermost faces of each axis are the tank's static solid walls.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/types.hpp"

namespace sc::flip {

template <int D>
using Index = std::array<int, D>;

/// One velocity array per axis: FaceField[a][face] is the component a on a face normal to axis a.
template <int D>
using FaceField = std::array<std::vector<double>, D>;

/// What a cell holds: no particle (air, p = 0), or fluid of the phase with the larger mass.
enum class Cell : std::uint8_t { Air = 0, Water = 1, Sand = 2 };

inline bool is_fluid(Cell c) { return c != Cell::Air; }

template <int D>
struct MacGrid {
  Vec<D> lo = Vec<D>::Zero();
  double dx = 1.0;
  Index<D> n{};  ///< cells per axis

  MacGrid() = default;
  /// The grid over the box [lo, hi]: n = round((hi − lo)/dx) ≥ 2 cells per axis, all of the width
  /// (hi₀ − lo₀)/n₀ (the box's extents should be multiples of dx).
  MacGrid(const Vec<D>& box_lo, const Vec<D>& box_hi, double cell_width);

  static std::size_t count(const Index<D>& dims) {
    std::size_t c = 1;
    for (int d = 0; d < D; ++d) c *= static_cast<std::size_t>(dims[d]);
    return c;
  }
  /// Flat index, axis 0 fastest.
  static std::size_t flat(const Index<D>& i, const Index<D>& dims) {
    std::size_t k = 0;
    for (int d = D - 1; d >= 0; --d) k = k * static_cast<std::size_t>(dims[d]) + static_cast<std::size_t>(i[d]);
    return k;
  }
  static Index<D> unflat(std::size_t k, const Index<D>& dims) {
    Index<D> i{};
    for (int d = 0; d < D; ++d) {
      i[d] = static_cast<int>(k % static_cast<std::size_t>(dims[d]));
      k /= static_cast<std::size_t>(dims[d]);
    }
    return i;
  }
  static bool inside(const Index<D>& i, const Index<D>& dims) {
    for (int d = 0; d < D; ++d)
      if (i[d] < 0 || i[d] >= dims[d]) return false;
    return true;
  }

  std::size_t cell_count() const { return count(n); }
  Index<D> face_dims(int a) const {
    Index<D> m = n;
    ++m[a];
    return m;
  }
  std::size_t face_count(int a) const { return count(face_dims(a)); }
  std::size_t cell(const Index<D>& c) const { return flat(c, n); }
  std::size_t face(int a, const Index<D>& f) const { return flat(f, face_dims(a)); }
  /// A face on the tank's boundary: its normal velocity is the wall's (zero).
  bool is_wall_face(int a, const Index<D>& f) const { return f[a] == 0 || f[a] == n[a]; }

  Vec<D> cell_centre(const Index<D>& c) const {
    Vec<D> x;
    for (int d = 0; d < D; ++d) x[d] = lo[d] + (c[d] + 0.5) * dx;
    return x;
  }
  Vec<D> face_centre(int a, const Index<D>& f) const {
    Vec<D> x;
    for (int d = 0; d < D; ++d) x[d] = lo[d] + (f[d] + (d == a ? 0.0 : 0.5)) * dx;
    return x;
  }
  /// The cell containing x (clamped to the grid).
  Index<D> cell_of(const Vec<D>& x) const {
    Index<D> c{};
    for (int d = 0; d < D; ++d) c[d] = std::clamp(static_cast<int>(std::floor((x[d] - lo[d]) / dx)), 0, n[d] - 1);
    return c;
  }
  FaceField<D> zero_faces() const {
    FaceField<D> u;
    for (int a = 0; a < D; ++a) u[a].assign(face_count(a), 0.0);
    return u;
  }

  /// The 2^D nodes around x and their multilinear weights, for the face values of component a
  /// (a = −1: the cell centres), clamped to the outermost nodes: a field's value at x is
  /// Σ weight·field[node].
  struct Stencil {
    std::array<std::size_t, (1 << D)> node;
    std::array<double, (1 << D)> weight;

    double of(const std::vector<double>& field) const {
      double value = 0.0;
      for (int corner = 0; corner < (1 << D); ++corner) value += weight[corner] * field[node[corner]];
      return value;
    }
  };
  Stencil stencil(int a, const Vec<D>& x) const {
    const Index<D> dims = a < 0 ? n : face_dims(a);
    Index<D> i0{};
    std::array<double, D> t{};
    for (int d = 0; d < D; ++d) {
      const double s = (x[d] - lo[d]) / dx - (d == a ? 0.0 : 0.5);
      i0[d] = std::clamp(static_cast<int>(std::floor(s)), 0, dims[d] - 2);
      t[d] = std::clamp(s - i0[d], 0.0, 1.0);
    }
    Stencil st{};
    const std::size_t base = flat(i0, dims);
    for (int corner = 0; corner < (1 << D); ++corner) {
      std::size_t k = base, stride = 1;
      double w = 1.0;
      for (int d = 0; d < D; ++d) {
        const bool up = (corner >> d) & 1;
        k += up ? stride : 0;
        stride *= static_cast<std::size_t>(dims[d]);
        w *= up ? t[d] : 1.0 - t[d];
      }
      st.node[corner] = k;
      st.weight[corner] = w;
    }
    return st;
  }
  /// Multilinear interpolation of the face values of component a at x [Zhu-Bridson 2005: Updating
  /// Particle Velocities] ("trilinearly interpolate"); exact for fields linear in x.
  double interpolate(int a, const std::vector<double>& field, const Vec<D>& x) const { return stencil(a, x).of(field); }
  /// Multilinear interpolation of cell-centred values (pressure) at x, clamped to the outermost
  /// cell centres.
  double interpolate_cells(const std::vector<double>& field, const Vec<D>& x) const { return stencil(-1, x).of(field); }
  Vec<D> velocity_at(const FaceField<D>& u, const Vec<D>& x) const {
    Vec<D> v;
    for (int a = 0; a < D; ++a) v[a] = interpolate(a, u[a], x);
    return v;
  }
  /// The velocities of the fields u and w at x (the stencils computed once).
  std::array<Vec<D>, 2> velocities_at(const FaceField<D>& u, const FaceField<D>& w, const Vec<D>& x) const {
    std::array<Vec<D>, 2> v;
    for (int a = 0; a < D; ++a) {
      const Stencil st = stencil(a, x);
      v[0][a] = st.of(u[a]);
      v[1][a] = st.of(w[a]);
    }
    return v;
  }
};

/// An axis-aligned box of the indices lo .. hi (inclusive) of a grid of `dims`, with the flat-index
/// stride of each axis: loops over the part of the grid where the material is.
template <int D>
struct IndexBox {
  Index<D> dims, lo, hi;
  std::array<long, D> stride{};

  IndexBox(const Index<D>& d, const Index<D>& l, const Index<D>& h) : dims(d), lo(l), hi(h) {
    stride[0] = 1;
    for (int a = 1; a < D; ++a) stride[a] = stride[a - 1] * dims[a - 1];
  }
  /// The smallest box holding every index k (flat) of `dims` with selected(k); empty if none.
  template <class Pred>
  static IndexBox around(const Index<D>& dims, Pred&& selected) {
    Index<D> l = dims, h{};
    h.fill(-1);
    Index<D> i{};
    for (std::size_t k = 0; k < MacGrid<D>::count(dims); ++k) {
      if (selected(k))
        for (int a = 0; a < D; ++a) {
          l[a] = std::min(l[a], i[a]);
          h[a] = std::max(h[a], i[a]);
        }
      for (int a = 0; a < D && ++i[a] == dims[a]; ++a) i[a] = 0;
    }
    return {dims, l, h};
  }
  bool empty() const {
    for (int a = 0; a < D; ++a)
      if (lo[a] > hi[a]) return true;
    return false;
  }
  /// The faces normal to axis a of the cells of this box (a box of cells): one more along a.
  IndexBox faces(int a) const {
    IndexBox f = *this;
    ++f.dims[a];
    ++f.hi[a];
    f.stride[0] = 1;
    for (int d = 1; d < D; ++d) f.stride[d] = f.stride[d - 1] * f.dims[d - 1];
    return f;
  }
  /// body(i, k) for every index of the box, the layers of the last axis shared among the threads:
  /// for loops whose every output belongs to one index.
  template <class Body>
  void parallel_for_each(Body&& body) const {
#pragma omp parallel for schedule(dynamic, 1)
    for (int layer = lo[D - 1]; layer <= hi[D - 1]; ++layer) {
      IndexBox s = *this;
      s.lo[D - 1] = s.hi[D - 1] = layer;
      s.sweep(0, body);
    }
  }
  /// Calls body(i, k) for every index i of the box (k its flat index), along axis a ascending when
  /// bit a of `order` is 0, else descending (the 2^D orders of a fast sweep): row by row along axis
  /// 0, the rows in the order of the other axes.
  template <class Body>
  void sweep(unsigned order, Body&& body) const {
    if (empty()) return;
    Index<D> f{};
    long k = 0;
    for (int a = 0; a < D; ++a) {
      f[a] = (order >> a) & 1 ? hi[a] : lo[a];
      k += f[a] * stride[a];
    }
    const int step = order & 1 ? -1 : 1, length = hi[0] - lo[0] + 1;
    while (true) {
      Index<D> i = f;
      for (long j = 0, kj = k; j < length; ++j, i[0] += step, kj += step) body(std::as_const(i), static_cast<std::size_t>(kj));
      int a = 1;
      for (; a < D; ++a) {
        const bool down = (order >> a) & 1;
        if (down ? f[a] > lo[a] : f[a] < hi[a]) {
          f[a] += down ? -1 : 1;
          k += down ? -stride[a] : stride[a];
          break;
        }
        const int start = down ? hi[a] : lo[a];
        k -= (f[a] - start) * stride[a];
        f[a] = start;
      }
      if (a == D) return;
    }
  }
};

template <int D>
MacGrid<D>::MacGrid(const Vec<D>& box_lo, const Vec<D>& box_hi, double cell_width) : lo(box_lo) {
  for (int d = 0; d < D; ++d) n[d] = std::max(2, static_cast<int>(std::lround((box_hi[d] - box_lo[d]) / cell_width)));
  dx = (box_hi[0] - box_lo[0]) / n[0];
}

}  // namespace sc::flip
