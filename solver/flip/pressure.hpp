// Pressure projection of the PIC/FLIP solver (Zhu & Bridson 2005) in physical units: solid tank
// walls (Neumann), free surface p = 0 in air cells (plain Dirichlet), fluid cells of water and sand
// with their own densities.
#pragma once
#include <vector>

#include "flip/mac_grid.hpp"

namespace sc::flip {

/// The fluid cells and their densities: label per cell and ρ per cell [kg/m^3] (0 in air).
template <int D>
struct CellState {
  std::vector<Cell> label;
  std::vector<double> density;
};

/// The density on face f (axis a) between the cells f − e_a and f: the mean over its fluid cells,
/// 0 when neither is fluid or f is a wall face.
template <int D>
double face_density(const MacGrid<D>& grid, const CellState<D>& cells, int a, const Index<D>& f);

/// Discrete divergence Σ_a (u_a(c + e_a) − u_a(c))/Δx per cell [1/s] (0 in air cells).
template <int D>
std::vector<double> divergence(const MacGrid<D>& grid, const CellState<D>& cells, const FaceField<D>& u);

struct ProjectionStats {
  long iterations = 0;
  double residual = 0.0;  ///< CG's relative residual
};

/// Pressure projection [Zhu-Bridson 2005: Solving on the Grid] ("enforce boundary conditions and
/// incompressibility"): solves, for every fluid cell c,
///   Σ_f k_f (p_c − p_nb(f)) = −(∇·u*)_c,   k_f = Δt/(ρ_f Δx²),
/// over its non-wall faces f (walls: ∂p/∂n from u·n = 0, Neumann; air neighbours p = 0), with
/// Eigen's conjugate gradient and an incomplete-Cholesky preconditioner to the relative residual
/// `tolerance`, then sets u_f ← u_f − Δt/(ρ_f Δx) (p_high − p_low) on every face next to fluid,
/// and u·n = 0 on the walls. `p` receives the pressure per cell [Pa] (0 in air).
template <int D>
ProjectionStats project(const MacGrid<D>& grid, const CellState<D>& cells, double dt, double tolerance,
                        long max_iterations, FaceField<D>& u, std::vector<double>& p);

}  // namespace sc::flip
