#include "flip/transfer.hpp"

#include <algorithm>
#include <cmath>

#include "sand/rigid_body.hpp"

namespace sc::flip {

template <int D>
void ParticleBins<D>::build(const MacGrid<D>& grid, std::span<const Vec<D>> x) {
  const std::size_t cells = grid.cell_count();
  std::vector<std::size_t> cell_of(x.size());
  start.assign(cells + 1, 0);
  for (std::size_t p = 0; p < x.size(); ++p) {
    cell_of[p] = grid.cell(grid.cell_of(x[p]));
    ++start[cell_of[p] + 1];
  }
  for (std::size_t c = 0; c < cells; ++c) start[c + 1] += start[c];
  std::vector<std::size_t> next(start.begin(), start.end() - 1);
  order.resize(x.size());
  for (std::size_t p = 0; p < x.size(); ++p) order[next[cell_of[p]]++] = p;
}

namespace {

/// The trilinear weight of [Zhu-Bridson 2005: Transferring to the Grid] between a particle at x
/// and a face at xf.
template <int D>
double hat_weight(const Vec<D>& x, const Vec<D>& xf, double dx) {
  double w = 1.0;
  for (int d = 0; d < D; ++d) w *= std::max(0.0, 1.0 - std::abs(x[d] - xf[d]) / dx);
  return w;
}

/// The particles' positions, masses and velocities in bin order, so that the particles of a row of
/// cells lie next to each other in memory.
template <int D>
struct BinnedParticles {
  VecArrayOf<D> x, v;
  std::vector<double> m;

  BinnedParticles(const ParticleBins<D>& bins, std::span<const Vec<D>> xs, std::span<const Vec<D>> vs,
                  std::span<const double> ms)
      : x(bins.order.size()), v(bins.order.size()), m(bins.order.size()) {
    for (std::size_t j = 0; j < bins.order.size(); ++j) {
      x[j] = xs[bins.order[j]];
      v[j] = vs[bins.order[j]];
      m[j] = ms[bins.order[j]];
    }
  }
};

/// Σ w m and Σ w m v_a over the particles within one cell width of face f (axis a): the cells
/// f − e_a and f along a, f − 1 .. f + 1 along the other axes, in fixed cell and particle order.
/// The cells of one row along axis 0 are consecutive bins: one range of binned particles per row.
template <int D>
std::pair<double, double> gather_face(const MacGrid<D>& grid, const ParticleBins<D>& bins,
                                      const BinnedParticles<D>& ps, int a, const Index<D>& f) {
  const Vec<D> xf = grid.face_centre(a, f);
  const int first = std::max(0, f[0] - 1), last = std::min(grid.n[0] - 1, f[0] + (a == 0 ? 0 : 1));
  Index<D> lo{}, rows{};
  rows[0] = 1;
  for (int d = 1; d < D; ++d) {
    lo[d] = f[d] - 1;
    rows[d] = d == a ? 2 : 3;
  }
  double wm = 0.0, wmv = 0.0;
  for (std::size_t r = 0; r < MacGrid<D>::count(rows); ++r) {
    Index<D> c = MacGrid<D>::unflat(r, rows);
    for (int d = 1; d < D; ++d) c[d] += lo[d];
    c[0] = first;
    if (!MacGrid<D>::inside(c, grid.n)) continue;
    const std::size_t k = grid.cell(c);
    for (std::size_t j = bins.start[k]; j < bins.start[k + static_cast<std::size_t>(last - first) + 1]; ++j) {
      const double w = hat_weight<D>(ps.x[j], xf, grid.dx) * ps.m[j];
      wm += w;
      wmv += w * ps.v[j][a];
    }
  }
  return {wm, wmv};
}

}  // namespace

template <int D>
void particles_to_grid(const MacGrid<D>& grid, const ParticleBins<D>& bins, std::span<const Vec<D>> x,
                       std::span<const Vec<D>> v, std::span<const double> m, FaceField<D>& u, FaceField<D>& weight) {
  const BinnedParticles<D> binned(bins, x, v, m);
  const IndexBox<D> occupied =
      IndexBox<D>::around(grid.n, [&](std::size_t c) { return bins.start[c + 1] > bins.start[c]; });
  for (int a = 0; a < D; ++a) {  // faces within one cell of a particle's cell: the others get nothing
    u[a].assign(grid.face_count(a), 0.0);
    weight[a].assign(grid.face_count(a), 0.0);
    Index<D> lo{}, hi{};
    for (int d = 0; d < D; ++d) {
      lo[d] = std::max(0, occupied.lo[d] - (d == a ? 0 : 1));
      hi[d] = std::min(grid.n[d] - (d == a ? 0 : 1), occupied.hi[d] + 1);
    }
    const IndexBox<D> box(grid.face_dims(a), lo, hi);
    box.parallel_for_each([&](const Index<D>& f, std::size_t k) {
      const auto [wm, wmv] = gather_face<D>(grid, bins, binned, a, f);
      weight[a][k] = wm;
      u[a][k] = wm > 0.0 ? wmv / wm : 0.0;
    });
  }
}

template <int D>
std::vector<Cell> label_cells(const MacGrid<D>& grid, const ParticleBins<D>& bins, std::span<const double> m,
                              std::span<const std::uint8_t> phase) {
  std::vector<Cell> label(grid.cell_count(), Cell::Air);
  for (std::size_t c = 0; c < label.size(); ++c) {
    double sand_mass = 0.0, water_mass = 0.0;
    for (const auto p : bins.in(c)) (phase[p] == static_cast<std::uint8_t>(Phase::Sand) ? sand_mass : water_mass) += m[p];
    if (sand_mass + water_mass > 0.0) label[c] = sand_mass >= water_mass ? Cell::Sand : Cell::Water;
  }
  return label;
}

namespace {

/// φ(x_c) = |x_c − x̄| − r̄ at the centre of cell c, x̄ and r̄ the k-weighted means of the particle
/// positions and radii within `reach`, k(s) = (1 − s²)³; Δx when no particle is within reach.
template <int D>
double surface_distance(const MacGrid<D>& grid, const ParticleBins<D>& bins, std::span<const Vec<D>> x,
                        std::span<const double> radius, double reach, const Index<D>& c) {
  const Vec<D> xc = grid.cell_centre(c);
  const int rings = static_cast<int>(std::ceil(reach / grid.dx));
  Index<D> extent{};
  extent.fill(2 * rings + 1);
  double w_sum = 0.0, r_sum = 0.0;
  Vec<D> x_sum = Vec<D>::Zero();
  for (std::size_t j = 0; j < MacGrid<D>::count(extent); ++j) {
    Index<D> nb = MacGrid<D>::unflat(j, extent);
    for (int d = 0; d < D; ++d) nb[d] += c[d] - rings;
    if (!MacGrid<D>::inside(nb, grid.n)) continue;
    for (const auto p : bins.in(grid.cell(nb))) {
      const double s2 = (x[p] - xc).squaredNorm() / (reach * reach);
      if (s2 >= 1.0) continue;
      const double w = (1.0 - s2) * (1.0 - s2) * (1.0 - s2);
      w_sum += w;
      x_sum += w * x[p];
      r_sum += w * radius[p];
    }
  }
  if (w_sum == 0.0) return grid.dx;
  return std::clamp((xc - x_sum / w_sum).norm() - r_sum / w_sum, 0.0, grid.dx);
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
