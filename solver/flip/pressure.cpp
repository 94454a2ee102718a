#include "flip/pressure.hpp"

#include <Eigen/IterativeLinearSolvers>
#include <algorithm>
#include <Eigen/Sparse>
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
#pragma omp parallel for schedule(static)
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
#pragma omp parallel for schedule(static)
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

/// Row of fluid cell c: its non-wall neighbours (cell index, or −1 for air) and coefficients k_f.
template <int D>
void assemble_row(const MacGrid<D>& grid, const CellState<D>& cells, const std::vector<long>& row_of, double dt,
                  const Index<D>& c, std::vector<Eigen::Triplet<double>>& triplets) {
  const long r = row_of[grid.cell(c)];
  double diag = 0.0;
  for (int a = 0; a < D; ++a)
    for (int side = 0; side < 2; ++side) {
      Index<D> f = c, nb = c;
      f[a] += side;
      nb[a] += side ? 1 : -1;
      if (grid.is_wall_face(a, f)) continue;
      const double k =
          dt / (face_density<D>(grid, cells, a, f) * surface_fraction<D>(grid, cells, a, f) * grid.dx * grid.dx);
      diag += k;
      const long rn = row_of[grid.cell(nb)];
      if (rn >= 0) triplets.emplace_back(r, rn, -k);
    }
  triplets.emplace_back(r, r, diag);
}

}  // namespace

template <int D>
ProjectionStats project(const MacGrid<D>& grid, const CellState<D>& cells, double dt, double tolerance,
                        long max_iterations, FaceField<D>& u, std::vector<double>& p) {
  for (int a = 0; a < D; ++a) {  // static walls: u·n = 0
    const Index<D> dims = grid.face_dims(a);
    for (std::size_t k = 0; k < u[a].size(); ++k)
      if (grid.is_wall_face(a, MacGrid<D>::unflat(k, dims))) u[a][k] = 0.0;
  }
  std::vector<long> row_of(grid.cell_count(), -1);
  std::vector<std::size_t> cell_of_row;
  for (std::size_t c = 0; c < row_of.size(); ++c)
    if (is_fluid(cells.label[c])) {
      row_of[c] = static_cast<long>(cell_of_row.size());
      cell_of_row.push_back(c);
    }
  p.assign(grid.cell_count(), 0.0);
  ProjectionStats stats;
  if (cell_of_row.empty()) return stats;

  const std::vector<double> div = divergence<D>(grid, cells, u);
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::VectorXd rhs(static_cast<Eigen::Index>(cell_of_row.size()));
  for (std::size_t r = 0; r < cell_of_row.size(); ++r) {
    assemble_row<D>(grid, cells, row_of, dt, MacGrid<D>::unflat(cell_of_row[r], grid.n), triplets);
    rhs[static_cast<Eigen::Index>(r)] = -div[cell_of_row[r]];
  }
  Eigen::SparseMatrix<double> A(rhs.size(), rhs.size());
  A.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper,
                           Eigen::IncompleteCholesky<double>>
      cg;
  cg.setTolerance(tolerance);
  cg.setMaxIterations(max_iterations);
  cg.compute(A);
  if (cg.info() != Eigen::Success) throw std::runtime_error("flip projection: incomplete Cholesky failed");
  const Eigen::VectorXd sol = cg.solve(rhs);
  stats.iterations = cg.iterations();
  stats.residual = cg.error();
  for (std::size_t r = 0; r < cell_of_row.size(); ++r) p[cell_of_row[r]] = sol[static_cast<Eigen::Index>(r)];

  for (int a = 0; a < D; ++a) {
    const Index<D> dims = grid.face_dims(a);
    const long faces = static_cast<long>(u[a].size());
#pragma omp parallel for schedule(static)
    for (long k = 0; k < faces; ++k) {
      Index<D> f = MacGrid<D>::unflat(static_cast<std::size_t>(k), dims);
      const double rho = face_density<D>(grid, cells, a, f);
      if (rho == 0.0) continue;
      const double theta = surface_fraction<D>(grid, cells, a, f);
      const double p_high = p[grid.cell(f)];
      --f[a];
      u[a][k] -= dt / (rho * theta * grid.dx) * (p_high - p[grid.cell(f)]);
    }
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
