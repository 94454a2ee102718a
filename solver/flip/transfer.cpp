#include "flip/transfer.hpp"

#include <algorithm>
#include <cmath>

#include <omp.h>

#include "sand/rigid_body.hpp"
#include "surface/implicit_surface.hpp"

namespace sc::flip {

template <int D>
void ParticleBins<D>::build(const MacGrid<D>& grid, std::span<const Vec<D>> x) {
  const std::size_t cells = grid.cell_count();
  const long n = static_cast<long>(x.size());
  std::vector<std::size_t> cell_of(x.size());
#pragma omp parallel for schedule(static)
  for (long p = 0; p < n; ++p) cell_of[p] = grid.cell(grid.cell_of(x[p]));
  start.assign(cells + 1, 0);
  for (const std::size_t c : cell_of) ++start[c + 1];
  for (std::size_t c = 0; c < cells; ++c) start[c + 1] += start[c];
  std::vector<std::size_t> next(start.begin(), start.end() - 1);
  order.resize(x.size());
  for (std::size_t p = 0; p < x.size(); ++p) order[next[cell_of[p]]++] = p;
}

namespace {

/// The particles' positions, masses and velocities in bin order: by cell, the cells in flat order.
template <int D>
struct BinnedParticles {
  VecArrayOf<D> x, v;
  std::vector<double> m;

  BinnedParticles(const ParticleBins<D>& bins, std::span<const Vec<D>> xs, std::span<const Vec<D>> vs,
                  std::span<const double> ms)
      : x(bins.order.size()), v(bins.order.size()), m(bins.order.size()) {
    const long n = static_cast<long>(bins.order.size());
#pragma omp parallel for schedule(static)
    for (long j = 0; j < n; ++j) {
      x[j] = xs[bins.order[j]];
      v[j] = vs[bins.order[j]];
      m[j] = ms[bins.order[j]];
    }
  }
};

/// The faces of component a around a particle at x in cell c with their trilinear weight factor
/// along each axis, max(0, 1 − |x_d − x_f,d|/Δx) [Zhu-Bridson 2005: Transferring to the Grid]: the
/// faces whose cells within one cell width include c (along a c and c + 1, along the other axes
/// c − 1 .. c + 1), along the last axis only the layers lo .. hi; those of factor 0 left out.
template <int D>
struct FaceStencil {
  std::array<std::array<long, 3>, D> offset;  // face index along d times the flat stride of d
  std::array<std::array<double, 3>, D> factor;
  Index<D> count{};

  FaceStencil(const MacGrid<D>& grid, int a, const Vec<D>& x, const Index<D>& c, int lo, int hi) {
    const Index<D> dims = grid.face_dims(a);
    long stride = 1;
    for (int d = 0; d < D; ++d) {
      const int first = std::max({0, d == D - 1 ? lo : 0, c[d] - (d == a ? 0 : 1)});
      const int last = std::min({dims[d] - 1, d == D - 1 ? hi : dims[d] - 1, c[d] + 1});
      for (int f = first; f <= last; ++f) {
        const double xf = grid.lo[d] + (f + (d == a ? 0.0 : 0.5)) * grid.dx;
        const double h = std::max(0.0, 1.0 - std::abs(x[d] - xf) / grid.dx);
        if (h > 0.0) {
          offset[d][count[d]] = f * stride;
          factor[d][count[d]++] = h;
        }
      }
      stride *= dims[d];
    }
  }
  /// body(k, w) for each face (k its flat index), w = Π_d factor_d multiplied in axis order.
  template <class Body>
  void for_each(Body&& body) const {
    for (int d = 0; d < D; ++d)
      if (count[d] == 0) return;
    Index<D> o{};
    while (true) {
      long k = 0;
      double w = 1.0;
      for (int d = 0; d < D; ++d) {
        k += offset[d][o[d]];
        w *= factor[d][o[d]];
      }
      body(static_cast<std::size_t>(k), w);
      int d = 0;
      for (; d < D && ++o[d] == count[d]; ++d) o[d] = 0;
      if (d == D) return;
    }
  }
};

/// Adds w m and w m v_a of the binned particles j in [first, last), in that order, to `wm` and
/// `wmv` on the faces of every component whose index along the last axis lies in [lo, hi]: a face
/// receives its particles in bin order whatever the slabs; terms of w = 0 are left out (they change
/// no sum).
template <int D>
void scatter(const MacGrid<D>& grid, const BinnedParticles<D>& ps, std::size_t first, std::size_t last, int lo, int hi,
             FaceField<D>& wm, FaceField<D>& wmv) {
  for (std::size_t j = first; j < last; ++j) {
    const Index<D> c = grid.cell_of(ps.x[j]);
    for (int a = 0; a < D; ++a)
      FaceStencil<D>(grid, a, ps.x[j], c, lo, hi).for_each([&](std::size_t k, double w) {
        w *= ps.m[j];
        wm[a][k] += w;
        wmv[a][k] += w * ps.v[j][a];
      });
  }
}

}  // namespace

template <int D>
void particles_to_grid(const MacGrid<D>& grid, const ParticleBins<D>& bins, std::span<const Vec<D>> x,
                       std::span<const Vec<D>> v, std::span<const double> m, FaceField<D>& u, FaceField<D>& weight) {
  const BinnedParticles<D> binned(bins, x, v, m);
  for (int a = 0; a < D; ++a) {
    u[a].assign(grid.face_count(a), 0.0);
    weight[a].assign(grid.face_count(a), 0.0);
  }
  // Threads own slabs of face layers along the last axis, of about equal particle counts, and
  // scatter the particles of the cell layers within one layer of their slab (one range of bins).
  const int top = grid.n[D - 1], slabs = x.empty() ? 0 : 2 * omp_get_max_threads();
  const std::size_t layer = grid.cell_count() / static_cast<std::size_t>(top), n = x.size();
  const auto first_layer = [&](int slab) {
    if (slab == 0) return 0;
    if (slab == slabs) return top + 1;
    return grid.cell_of(binned.x[n * static_cast<std::size_t>(slab) / static_cast<std::size_t>(slabs)])[D - 1];
  };
#pragma omp parallel for schedule(dynamic, 1)
  for (int slab = 0; slab < slabs; ++slab) {
    const int lo = first_layer(slab), hi = first_layer(slab + 1) - 1;
    if (lo > hi) continue;
    const std::size_t first = bins.start[static_cast<std::size_t>(std::max(0, lo - 1)) * layer];
    const std::size_t last = bins.start[static_cast<std::size_t>(std::min(top, hi + 2)) * layer];
    scatter<D>(grid, binned, first, last, lo, hi, weight, u);
  }
  for (int a = 0; a < D; ++a) {
    const long faces = static_cast<long>(u[a].size());
#pragma omp parallel for schedule(static)
    for (long k = 0; k < faces; ++k)
      if (weight[a][k] > 0.0) u[a][k] /= weight[a][k];
  }
}

template <int D>
std::vector<Cell> label_cells(const MacGrid<D>& grid, const ParticleBins<D>& bins, std::span<const double> m,
                              std::span<const std::uint8_t> phase) {
  std::vector<Cell> label(grid.cell_count(), Cell::Air);
  const long cells = static_cast<long>(label.size());
#pragma omp parallel for schedule(static)
  for (long c = 0; c < cells; ++c) {
    double sand_mass = 0.0, water_mass = 0.0;
    for (const auto p : bins.in(c)) (phase[p] == static_cast<std::uint8_t>(Phase::Sand) ? sand_mass : water_mass) += m[p];
    if (sand_mass + water_mass > 0.0) label[c] = sand_mass >= water_mass ? Cell::Sand : Cell::Water;
  }
  return label;
}

namespace {

/// φ(x_c) of surface/implicit_surface.hpp at the centre of cell c, the particles within `reach`;
/// clamped to [0, Δx], and Δx when no particle is within reach.
template <int D>
double surface_distance(const MacGrid<D>& grid, const ParticleBins<D>& bins, std::span<const Vec<D>> x,
                        std::span<const double> radius, double reach, const Index<D>& c) {
  const Vec<D> xc = grid.cell_centre(c);
  const int rings = static_cast<int>(std::ceil(reach / grid.dx));
  Index<D> extent{};
  extent.fill(2 * rings + 1);
  surface::SurfaceAverage<D> average(xc, reach);
  for (std::size_t j = 0; j < MacGrid<D>::count(extent); ++j) {
    Index<D> nb = MacGrid<D>::unflat(j, extent);
    for (int d = 0; d < D; ++d) nb[d] += c[d] - rings;
    if (!MacGrid<D>::inside(nb, grid.n)) continue;
    for (const auto p : bins.in(grid.cell(nb))) average.add(x[p], radius[p]);
  }
  if (average.empty()) return grid.dx;
  return std::clamp(average.phi(), 0.0, grid.dx);
}

/// Whether cell c has a fluid cell across one of its faces: only such air cells have a face between
/// fluid and air, the one place the surface distance is read (pressure.cpp surface_fraction).
template <int D>
bool borders_fluid(const MacGrid<D>& grid, const std::vector<Cell>& label, const Index<D>& c) {
  for (int a = 0; a < D; ++a)
    for (const int s : {-1, 1}) {
      Index<D> nb = c;
      nb[a] += s;
      if (MacGrid<D>::inside(nb, grid.n) && is_fluid(label[grid.cell(nb)])) return true;
    }
  return false;
}

}  // namespace

template <int D>
std::vector<double> air_distance(const MacGrid<D>& grid, const ParticleBins<D>& bins, std::span<const Vec<D>> x,
                                 std::span<const double> radius, const std::vector<Cell>& label) {
  std::vector<double> phi(grid.cell_count(), grid.dx);
  if (radius.empty()) return phi;
  double mean_radius = 0.0;
  for (const double r : radius) mean_radius += r;
  const double reach = 4.0 * mean_radius / static_cast<double>(radius.size());  // twice the mean spacing
  const IndexBox<D> fluid = IndexBox<D>::around(grid.n, [&](std::size_t k) { return is_fluid(label[k]); });
  Index<D> lo{}, hi{};  // the air cells next to fluid are within one cell of the fluid's box
  for (int d = 0; d < D; ++d) {
    lo[d] = std::max(0, fluid.lo[d] - 1);
    hi[d] = std::min(grid.n[d] - 1, fluid.hi[d] + 1);
  }
  IndexBox<D>(grid.n, lo, hi).parallel_for_each([&](const Index<D>& c, std::size_t k) {
    if (!is_fluid(label[k]) && borders_fluid<D>(grid, label, c))
      phi[k] = surface_distance<D>(grid, bins, x, radius, reach, c);
  });
  return phi;
}

template <int D>
Vec<D> grid_to_particle(const Vec<D>& pic, const Vec<D>& old, const Vec<D>& v, double flip_ratio) {
  const Vec<D> change = pic - old;
  return (1.0 - flip_ratio) * pic + flip_ratio * (v + change);
}

template <int D>
Vec<D> advect_rk2(const MacGrid<D>& grid, const FaceField<D>& u, const Vec<D>& x, const Vec<D>& u_x, double dt) {
  const Vec<D> mid = x + 0.5 * dt * u_x;
  Vec<D> out = x + dt * grid.velocity_at(u, mid);
  const double margin = 0.1 * grid.dx;
  for (int d = 0; d < D; ++d)
    out[d] = std::clamp(out[d], grid.lo[d] + margin, grid.lo[d] + grid.n[d] * grid.dx - margin);
  return out;
}

#define SC_FLIP_TRANSFER(D)                                                                                     \
  template struct ParticleBins<D>;                                                                              \
  template void particles_to_grid<D>(const MacGrid<D>&, const ParticleBins<D>&, std::span<const Vec<D>>,       \
                                     std::span<const Vec<D>>, std::span<const double>, FaceField<D>&,          \
                                     FaceField<D>&);                                                            \
  template std::vector<Cell> label_cells<D>(const MacGrid<D>&, const ParticleBins<D>&, std::span<const double>, \
                                            std::span<const std::uint8_t>);                                    \
  template std::vector<double> air_distance<D>(const MacGrid<D>&, const ParticleBins<D>&, std::span<const Vec<D>>, \
                                              std::span<const double>, const std::vector<Cell>&);              \
  template Vec<D> grid_to_particle<D>(const Vec<D>&, const Vec<D>&, const Vec<D>&, double);                  \
  template Vec<D> advect_rk2<D>(const MacGrid<D>&, const FaceField<D>&, const Vec<D>&, const Vec<D>&, double);
SC_FLIP_TRANSFER(2)
SC_FLIP_TRANSFER(3)
#undef SC_FLIP_TRANSFER

}  // namespace sc::flip
