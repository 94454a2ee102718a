// Pressure projection of the PIC/FLIP solver (Zhu & Bridson 2005) in physical units: solid tank
// walls (Neumann), free surface p = 0 placed between fluid and air cells by the ghost-fluid method,
// fluid cells of water and sand with their own densities.
#pragma once
#include <vector>

#include "flip/mac_grid.hpp"

namespace sc::flip {

/// The fluid cells and their densities: label per cell and ρ per cell [kg/m^3] (0 in air), and per
/// air cell the distance from its centre to the free surface [m] (transfer.hpp air_distance; empty:
/// the surface lies at the air cell centres).
template <int D>
struct CellState {
  std::vector<Cell> label;
  std::vector<double> density;
  std::vector<double> air_distance;
};

/// The fraction θ ∈ [θ_min, 1] of the face f's (axis a) cell-centre span that lies in fluid
/// [Zhu-Bridson 2005: free surface]: 1 unless exactly one of the cells f − e_a and f is fluid; then
/// θ = 1 − φ_air/Δx, with φ_air the air cell's distance to the surface (the ghost-fluid position of
/// p = 0, Gibou et al. 2002 as in Bridson's solver), at least θ_min = 0.01 so that p stays bounded.
template <int D>
double surface_fraction(const MacGrid<D>& grid, const CellState<D>& cells, int a, const Index<D>& f);

/// The pressure of the fluid cells extended to their air neighbours by the ghost values of the
/// free-surface condition [Zhu-Bridson 2005: free surface], p_air = p_fluid (1 − 1/θ) (mean over its fluid face neighbours), so that
/// interpolation between a fluid and an air cell centre passes through p = 0 at the surface.
template <int D>
std::vector<double> ghost_pressure(const MacGrid<D>& grid, const CellState<D>& cells, const std::vector<double>& p);

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
/// over its non-wall faces f (walls: ∂p/∂n from u·n = 0, Neumann; air neighbours: p = 0 on the
/// surface, a distance θ Δx from c, so k_f = Δt/(ρ_f θ Δx²), surface_fraction), with
/// a conjugate gradient preconditioned by modified incomplete Cholesky (MIC(0)) to the relative residual
/// `tolerance`, then sets u_f ← u_f − Δt/(ρ_f θ Δx) (p_high − p_low) on every face next to fluid,
/// and u·n = 0 on the walls. `p` receives the pressure per cell [Pa] (0 in air).
template <int D>
ProjectionStats project(const MacGrid<D>& grid, const CellState<D>& cells, double dt, double tolerance,
                        long max_iterations, FaceField<D>& u, std::vector<double>& p);

}  // namespace sc::flip
