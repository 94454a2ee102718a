// The sand step of Zhu & Bridson 2005 on the MAC grid, after the pressure projection: strain rate
// per sand cell, the rigid stress and the yield test, the frictional stress of flowing cells, the
// Coulomb wall condition, and the projection of connected rigid cells onto rigid motions.
// The stress formulas are the suite's one home for them (sand/yield.hpp, sand/frictional_stress.hpp,
// compression positive); this file evaluates them on grid cells.
#pragma once
#include <vector>

#include "flip/pressure.hpp"
#include "sand/rigid_body.hpp"
#include "sand/sand_params.hpp"

namespace sc::flip {

template <int D>
using MatArray = std::vector<Mat<D>, Eigen::aligned_allocator<Mat<D>>>;

/// The Coulomb coefficient μ_w of each tank side, index 2a + 1 for the upper side of axis a:
/// the case's wall friction on rough (no-slip) sides, 0 on slip and open ones.
template <int D>
using SideFriction = std::array<double, 2 * D>;

/// Strain rate D = (∇u + ∇uᵀ)/2 at the centre of cell c [1/s] [Zhu-Bridson 2005: strain rate]
/// (slide "Frictional stress"): ∂u_a/∂x_a from the cell's two a-faces; ∂u_a/∂x_b (b ≠ a) from the
/// cell-centred u_a of the neighbours along b, central where both are fluid, one-sided where one is.
template <int D>
Mat<D> cell_strain_rate(const MacGrid<D>& grid, const CellState<D>& cells, const FaceField<D>& u, const Index<D>& c);

/// Per cell: sand that yields (flows) and sand that is rigid, and the stress (tension positive,
/// −σ of the compression-positive convention) that flowing cells exert (only read where yielding).
template <int D>
struct SandCells {
  std::vector<std::uint8_t> yielding, rigid;
  MatArray<D> stress;
};

/// Yield classification [Zhu-Bridson 2005: rigid stress] [Zhu-Bridson 2005: yield condition]: per
/// sand cell the rigid stress σ_rigid = −ρ D Δx²/Δt (the stress that stops all sliding within one
/// step, sand/yield.hpp rigid_stress), the Mohr-Coulomb test with the projection pressure
/// (sand/yield.hpp is_rigid, strength factor of the case's yield surface, cohesion c); a flowing cell
/// stores the frictional stress σ_f = −sin φ p D/(√(1/3)|D|_F) [Zhu-Bridson 2005: frictional stress]
/// (sand/frictional_stress.hpp).
/// `out` is reused from step to step: its stress array is only resized.
template <int D>
void classify_sand(const MacGrid<D>& grid, const CellState<D>& cells, const FaceField<D>& u,
                   const std::vector<double>& p, const SandParams& sand, double dt, SandCells<D>& out);

/// Velocity update by the frictional stress of flowing cells [Zhu-Bridson 2005: frictional stress]:
/// u_f ← u_f + Δt/ρ_f (∇·τ)_a on every non-wall face next to a flowing cell, with τ = −σ_f at cell
/// centres (0 elsewhere), ∂τ_aa/∂x_a across the face and ∂τ_ab/∂x_b between the edge values: the
/// mean of the four cells around the edge when all four are sand, else 0 (an edge on the sand's
/// boundary carries no stress: the free surface and water are traction-free, and a wall's traction
/// is its Coulomb condition, wall_friction).
template <int D>
void apply_frictional_stress(const MacGrid<D>& grid, const CellState<D>& cells, const SandCells<D>& sand_cells,
                             double dt, FaceField<D>& u);

/// Normal stress of a wall on the sand cell c next to it (axis a, side 0 below / 1 above) [Pa]
/// [Zhu-Bridson 2005: Frictional Boundary Conditions]: the cell's pressure plus the half cell
/// between its centre and the wall stopped by the wall, ρ Δx/(2Δt) times the normal velocity into
/// the wall that the boundary condition removed (`before`: the velocities before the projection).
/// For sand at rest it is the pressure at the wall, ρ g d; for a layer thinner than a cell, whose
/// centre pressure is about 0, it still carries the layer's weight.
template <int D>
double wall_normal_stress(const MacGrid<D>& grid, const CellState<D>& cells, const std::vector<double>& p,
                          const FaceField<D>& before, double dt, int a, int side, const Index<D>& c);

/// Coulomb friction of the walls on flowing sand [Zhu-Bridson 2005: Frictional Boundary Conditions]:
/// on the faces tangent to a wall of μ_w > 0 in the cell layer next to it, the tangential velocity
/// shrinks by at most μ_w σ_n Δt/(ρ Δx) (the wall's tangential impulse per unit mass, σ_n the mean
/// wall_normal_stress of the face's two cells) and never reverses. Component by component in 3-D.
template <int D>
void wall_friction(const MacGrid<D>& grid, const CellState<D>& cells, const SandCells<D>& sand_cells,
                   const std::vector<double>& p, const FaceField<D>& before, const SideFriction<D>& mu, double dt,
                   FaceField<D>& u);

/// Connected groups of rigid sand cells (face neighbours), by flood fill in cell order
/// [Zhu-Bridson 2005: rigid groups] (slide "Simulation algorithm": "project connected rigid groups").
template <int D>
std::vector<std::vector<std::size_t>> rigid_groups(const MacGrid<D>& grid, const std::vector<std::uint8_t>& rigid);

/// A group's faces (all faces of its cells) with their masses ρ Δx^D/2 per adjacent group cell;
/// wall faces carry the group's momentum towards the wall but keep the wall's velocity.
struct GroupFace {
  int axis;
  std::size_t index;
  double mass;
  bool wall;
};

/// The rigid motion of a group: velocity, and angular velocity about `centre`.
template <int D>
struct RigidFit {
  Vec<D> centre = Vec<D>::Zero();
  Vec<D> velocity = Vec<D>::Zero();
  AngVec<D> omega = AngVec<D>::Zero();
};

template <int D>
std::vector<GroupFace> group_faces(const MacGrid<D>& grid, const CellState<D>& cells,
                                   const std::vector<std::size_t>& group);

/// Rigid-group projection [Zhu-Bridson 2005: rigid groups]: the rigid motion (v, ω) nearest to the
/// group's face velocities in the mass-weighted least-squares sense, Σ_f m_f (u_f − (v + ω × r_f)_a)²
/// minimal. Its normal equations state that Σ m_f u_f and Σ m_f r_f × u_f e_a (the group's linear
/// and angular momentum) are the same for u and for the rigid motion: both are conserved.
template <int D>
RigidFit<D> fit_rigid_motion(const MacGrid<D>& grid, const std::vector<GroupFace>& faces, const Vec<D>& centre,
                             const FaceField<D>& u);

/// Coulomb friction of the walls on a rigid group [Zhu-Bridson 2005: Frictional Boundary
/// Conditions] applied to the group as one body, with the paper's normal impulse: the normal
/// velocity the boundary condition removed. For each wall the group's cells touch, the group may
/// not move into the wall (its normal velocity v_n is clipped at 0), and the impulse is the change
/// of v_n from before the projection (`before`: the rigid fit of the velocities before it),
/// N = M_a Δv_n with M_a the mass of the group's a-faces; on a wall of μ_w > 0 the
/// tangential momentum (M_b v_b) shrinks by μ_w N, and a group whose tangential momentum friction can
/// absorb stops altogether (a group resting on a static solid stays at rest); slip walls only
/// stop the normal motion.
template <int D>
void group_wall_friction(const MacGrid<D>& grid, const std::vector<std::size_t>& group,
                         const std::vector<GroupFace>& faces, const RigidFit<D>& before,
                         const SideFriction<D>& mu, RigidFit<D>& fit);

/// Sets every non-wall face of the group to the rigid motion's velocity component at its centre.
template <int D>
void apply_rigid_motion(const MacGrid<D>& grid, const std::vector<GroupFace>& faces, const RigidFit<D>& fit,
                        FaceField<D>& u);

}  // namespace sc::flip
