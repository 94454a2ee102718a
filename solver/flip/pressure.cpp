#include "flip/pressure.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace sc::flip {

template <int D>
double face_density(const MacGrid<D>& grid, const CellState<D>& cells, int a, const Index<D>& f) {
  if (grid.is_wall_face(a, f)) return 0.0;
  Index<D> below = f;
  --below[a];
  const std::size_t c0 = grid.cell(below), c1 = grid.cell(f);
  const bool f0 = is_fluid(cells.label[c0]), f1 = is_fluid(cells.label[c1]);
  if (f0 && f1) return 0.5 * (cells.density[c0] + cells.density[c1]);
  return f0 ? cells.density[c0] : (f1 ? cells.density[c1] : 0.0);
}

template <int D>
double surface_fraction(const MacGrid<D>& grid, const CellState<D>& cells, int a, const Index<D>& f) {
  if (cells.air_distance.empty() || grid.is_wall_face(a, f)) return 1.0;
  Index<D> below = f;
  --below[a];
  const std::size_t c0 = grid.cell(below), c1 = grid.cell(f);
  const bool f0 = is_fluid(cells.label[c0]), f1 = is_fluid(cells.label[c1]);
  if (f0 == f1) return 1.0;
  return std::clamp(1.0 - cells.air_distance[f0 ? c1 : c0] / grid.dx, 0.01, 1.0);
}

template <int D>
std::vector<double> ghost_pressure(const MacGrid<D>& grid, const CellState<D>& cells, const std::vector<double>& p) {
  std::vector<double> out = p;
  const long n = static_cast<long>(p.size());
#pragma omp parallel for schedule(dynamic, 4096)
  for (long k = 0; k < n; ++k) {
    if (is_fluid(cells.label[k])) continue;
    const Index<D> c = MacGrid<D>::unflat(static_cast<std::size_t>(k), grid.n);
    double sum = 0.0, count = 0.0;
    for (int a = 0; a < D; ++a)
      for (const int side : {0, 1}) {
        Index<D> nb = c, f = c;
        nb[a] += side ? 1 : -1;
        f[a] += side;
        if (!MacGrid<D>::inside(nb, grid.n) || !is_fluid(cells.label[grid.cell(nb)])) continue;
        sum += p[grid.cell(nb)] * (1.0 - 1.0 / surface_fraction<D>(grid, cells, a, f));
        count += 1.0;
      }
    out[k] = count > 0.0 ? sum / count : 0.0;
  }
  return out;
}

template <int D>
std::vector<double> divergence(const MacGrid<D>& grid, const CellState<D>& cells, const FaceField<D>& u) {
  std::vector<double> div(grid.cell_count(), 0.0);
  const long n = static_cast<long>(div.size());
#pragma omp parallel for schedule(dynamic, 4096)
  for (long k = 0; k < n; ++k) {
    if (!is_fluid(cells.label[k])) continue;
    const Index<D> c = MacGrid<D>::unflat(static_cast<std::size_t>(k), grid.n);
    double s = 0.0;
    for (int a = 0; a < D; ++a) {
      Index<D> up = c;
      ++up[a];
      s += u[a][grid.face(a, up)] - u[a][grid.face(a, c)];
    }
    div[k] = s / grid.dx;
  }
  return div;
}

namespace {

/// The pressure matrix A of the fluid cells, rows in cell order: per row its diagonal and, per
/// side 2a + s of the cell (s = 1: above along a), the row of the fluid neighbour across it (−1:
/// none) and the coefficient −k_f. Symmetric: a face between two fluid cells has one k_f.
template <int D>
struct PoissonRows {
  std::vector<std::size_t> cell;
  std::vector<double> diag;
  std::vector<std::array<long, 2 * D>> nb;
  std::vector<std::array<double, 2 * D>> off;

  std::size_t size() const { return cell.size(); }
};

template <int D>
PoissonRows<D> assemble(const MacGrid<D>& grid, const CellState<D>& cells, double dt) {
  PoissonRows<D> A;
  std::vector<long> row_of(grid.cell_count(), -1);
  for (std::size_t c = 0; c < row_of.size(); ++c)
    if (is_fluid(cells.label[c])) {
      row_of[c] = static_cast<long>(A.cell.size());
      A.cell.push_back(c);
    }
  A.diag.assign(A.size(), 0.0);
  A.nb.resize(A.size());
  A.off.resize(A.size());
  const long rows = static_cast<long>(A.size());
#pragma omp parallel for schedule(static)
  for (long r = 0; r < rows; ++r) {
    const Index<D> c = MacGrid<D>::unflat(A.cell[r], grid.n);
    for (int a = 0; a < D; ++a)
      for (int side = 0; side < 2; ++side) {
        Index<D> f = c, nb = c;
        f[a] += side;
        nb[a] += side ? 1 : -1;
        A.nb[r][2 * a + side] = -1;
        A.off[r][2 * a + side] = 0.0;
        if (grid.is_wall_face(a, f)) continue;
        const double k =
            dt / (face_density<D>(grid, cells, a, f) * surface_fraction<D>(grid, cells, a, f) * grid.dx * grid.dx);
        A.diag[r] += k;
        const long rn = row_of[grid.cell(nb)];
        if (rn < 0) continue;
        A.nb[r][2 * a + side] = rn;
        A.off[r][2 * a + side] = -k;
      }
  }
  return A;
}

template <int D>
void multiply(const PoissonRows<D>& A, const std::vector<double>& x, std::vector<double>& y) {
  for (std::size_t r = 0; r < A.size(); ++r) {
    double s = A.diag[r] * x[r];
    for (int j = 0; j < 2 * D; ++j)
      if (A.nb[r][j] >= 0) s += A.off[r][j] * x[A.nb[r][j]];
    y[r] = s;
  }
}

double dot(const std::vector<double>& x, const std::vector<double>& y) {
  double s = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) s += x[i] * y[i];
  return s;
}

/// The modified incomplete Cholesky factor MIC(0) of A in row order, A ≈ L Lᵀ with L's sparsity
/// that of A's lower part (R. Bridson, Fluid Simulation for Computer Graphics, 2nd ed., §5.2.3:
/// tuning τ = 0.97, safety σ = 0.25): per row 1/L_rr, the off-diagonal entries of L being
/// A_rs/L_ss.
template <int D>
std::vector<double> mic0(const PoissonRows<D>& A) {
  constexpr double tau = 0.97, sigma = 0.25;
  std::vector<double> precon(A.size(), 0.0);
  for (std::size_t r = 0; r < A.size(); ++r) {
    double e = A.diag[r];
    for (int a = 0; a < D; ++a) {
      const long lo = A.nb[r][2 * a];
      if (lo < 0) continue;
      const double q = A.off[lo][2 * a + 1] * precon[lo];
      double across = 0.0;  // lo's couplings to its upper neighbours along the other axes
      for (int b = 0; b < D; ++b)
        if (b != a) across += A.off[lo][2 * b + 1];
      e -= q * q + tau * A.off[lo][2 * a + 1] * across * precon[lo] * precon[lo];
    }
    if (e < sigma * A.diag[r]) e = A.diag[r];
    precon[r] = 1.0 / std::sqrt(e);
  }
  return precon;
}

/// z = (L Lᵀ)⁻¹ r with the MIC(0) factor: forward then backward substitution in row order.
template <int D>
void apply_mic0(const PoissonRows<D>& A, const std::vector<double>& precon, const std::vector<double>& r,
                std::vector<double>& z) {
  const long n = static_cast<long>(A.size());
  for (long i = 0; i < n; ++i) {
    double t = r[i];
    for (int a = 0; a < D; ++a) {
      const long lo = A.nb[i][2 * a];
      if (lo >= 0) t -= A.off[lo][2 * a + 1] * precon[lo] * z[lo];
    }
    z[i] = t * precon[i];
  }
  for (long i = n - 1; i >= 0; --i) {
    double t = z[i];
    for (int a = 0; a < D; ++a) {
      const long hi = A.nb[i][2 * a + 1];
      if (hi >= 0) t -= A.off[i][2 * a + 1] * precon[i] * z[hi];
    }
    z[i] = t * precon[i];
  }
}

/// Preconditioned conjugate gradient from x = 0 to ‖b − A x‖ ≤ tolerance ‖b‖. Serial: an iteration
/// is too short for the fork and join of threads to pay, and its sums run in one fixed order.
template <int D>
ProjectionStats solve_pcg(const PoissonRows<D>& A, const std::vector<double>& b, double tolerance,
                          long max_iterations, std::vector<double>& x) {
  ProjectionStats stats;
  const std::size_t n = A.size();
  x.assign(n, 0.0);
  const double b_norm2 = dot(b, b);
  if (b_norm2 == 0.0) return stats;
  const std::vector<double> precon = mic0<D>(A);
  std::vector<double> r = b, z(n), s(n), q(n);
  apply_mic0<D>(A, precon, r, z);
  s = z;
  double rz = dot(r, z), r_norm2 = b_norm2;
  while (stats.iterations < max_iterations && r_norm2 > tolerance * tolerance * b_norm2) {
    multiply<D>(A, s, q);
    const double alpha = rz / dot(s, q);
    for (std::size_t i = 0; i < n; ++i) {
      x[i] += alpha * s[i];
      r[i] -= alpha * q[i];
    }
    ++stats.iterations;
    r_norm2 = dot(r, r);
    if (r_norm2 <= tolerance * tolerance * b_norm2) break;
    apply_mic0<D>(A, precon, r, z);
    const double rz_new = dot(r, z), beta = rz_new / rz;
    rz = rz_new;
    for (std::size_t i = 0; i < n; ++i) s[i] = z[i] + beta * s[i];
  }
  stats.residual = std::sqrt(r_norm2 / b_norm2);
  return stats;
}

}  // namespace

template <int D>
ProjectionStats project(const MacGrid<D>& grid, const CellState<D>& cells, double dt, double tolerance,
                        long max_iterations, FaceField<D>& u, std::vector<double>& p) {
  for (int a = 0; a < D; ++a)  // static walls: u·n = 0
    for (const int side : {0, grid.n[a]}) {
      Index<D> lo{}, hi = grid.n;
      for (int d = 0; d < D; ++d) hi[d] -= d == a ? 0 : 1;
      lo[a] = hi[a] = side;
      IndexBox<D>(grid.face_dims(a), lo, hi).sweep(0, [&](const Index<D>&, std::size_t k) { u[a][k] = 0.0; });
    }
  p.assign(grid.cell_count(), 0.0);
  const PoissonRows<D> A = assemble<D>(grid, cells, dt);
  if (A.size() == 0) return {};
  const std::vector<double> div = divergence<D>(grid, cells, u);
  std::vector<double> rhs(A.size()), sol;
  for (std::size_t r = 0; r < A.size(); ++r) rhs[r] = -div[A.cell[r]];
  const ProjectionStats stats = solve_pcg<D>(A, rhs, tolerance, max_iterations, sol);
  if (!std::isfinite(stats.residual)) throw std::runtime_error("flip projection: the pressure solve diverged");
  for (std::size_t r = 0; r < A.size(); ++r) p[A.cell[r]] = sol[r];

  const IndexBox<D> fluid = IndexBox<D>::around(grid.n, [&](std::size_t c) { return is_fluid(cells.label[c]); });
  for (int a = 0; a < D; ++a) {  // the faces next to fluid
    fluid.faces(a).parallel_for_each([&](const Index<D>& face, std::size_t k) {
      const double rho = face_density<D>(grid, cells, a, face);
      if (rho == 0.0) return;
      const double theta = surface_fraction<D>(grid, cells, a, face);
      Index<D> below = face;
      --below[a];
      u[a][k] -= dt / (rho * theta * grid.dx) * (p[grid.cell(face)] - p[grid.cell(below)]);
    });
  }
  return stats;
}

#define SC_FLIP_PRESSURE(D)                                                                                       \
  template double face_density<D>(const MacGrid<D>&, const CellState<D>&, int, const Index<D>&);                \
  template double surface_fraction<D>(const MacGrid<D>&, const CellState<D>&, int, const Index<D>&);            \
  template std::vector<double> ghost_pressure<D>(const MacGrid<D>&, const CellState<D>&, const std::vector<double>&); \
  template std::vector<double> divergence<D>(const MacGrid<D>&, const CellState<D>&, const FaceField<D>&);      \
  template ProjectionStats project<D>(const MacGrid<D>&, const CellState<D>&, double, double, long, FaceField<D>&, \
                                      std::vector<double>&);
SC_FLIP_PRESSURE(2)
SC_FLIP_PRESSURE(3)
#undef SC_FLIP_PRESSURE

}  // namespace sc::flip
