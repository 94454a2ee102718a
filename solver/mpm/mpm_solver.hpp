// Two-grid MPM for sand and water after Tampubolon et al. 2017: each phase is transferred to its own
// grid (co-located, same nodes) by APIC with quadratic B-splines and MLS-MPM forces, the grids
// exchange momentum implicitly where both have mass, and each phase's boundary rule is applied
// before the velocities go back to the particles (docs/equations.md §9).
#pragma once
#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include "core/stage_timers.hpp"
#include "mpm/bspline.hpp"
#include "mpm/constitutive.hpp"
#include "mpm/grid.hpp"
#include "mpm/particles.hpp"

namespace sc::mpm {

/// The numbers of one MPM run, SI units.
template <int D>
struct Params {
  Grid<D> grid;
  Vec<D> wall_lo = Vec<D>::Zero(), wall_hi = Vec<D>::Zero();  ///< planes the material stays within
  std::array<bool, 2 * D> rough{};  ///< sides (2d: at wall_lo[d], 2d + 1: at wall_hi[d]) where sand feels Coulomb friction
  double wall_friction = 0.0;       ///< Coulomb coefficient of the rough sides
  /// Boxes [lo, hi] whose grid nodes clamp the sand: its velocity there is zero, in tension as in
  /// compression, and the water drags on it as on an immovable skeleton (a bar's held end, a fixed bed).
  std::vector<std::array<Vec<D>, 2>> clamps;
  Vec<D> gravity = Vec<D>::Zero();
  SandModel sand;
  double cohesion = 0.0;            ///< dry cohesion c0 [Pa]
  bool wet_cohesion_loss = true;    ///< c = c0 (1 − s)
  double sand_density = 0.0;        ///< [kg/m^3] (for the elastic wave speed)
  double water_density = 1000.0;    ///< ρ0 of water [kg/m^3]
  EquationOfState eos;              ///< water's pressure at density ρ0/J
  double porosity = 0.4;            ///< n of the sand
  double drag = 0.0;                ///< c_E [kg m⁻³ s⁻¹] (exchange.hpp drag_per_volume)
  double cfl = 0.4;                 ///< substep Δt = cfl h / (wave speed + largest particle speed)
  double relax_until = 0.0;         ///< [s] before this, grid velocities decay at relax_rate
  double relax_rate = 0.0;          ///< [1/s]
};

enum class MpmStage { Transfer, Stress, Grid, Exchange, Count };
inline constexpr std::array<std::string_view, static_cast<std::size_t>(MpmStage::Count)> mpm_stage_names = {
    "transfer", "stress", "grid", "exchange"};

/// The two grids' nodal state: mass, volume Σ w V0 and velocity of each phase, the saturation, and
/// where both phases are present the porosity and the water's pressure p_i = Σ w m p / Σ w m.
template <int D>
struct Nodes {
  std::vector<double> m_s, m_w, V_s, V_w, saturation, porosity, pressure;
  std::vector<Vec<D>> v_s, v_w;
  void resize(std::size_t n);
};

template <int D>
class MpmSolver {
 public:
  MpmSolver(Params<D> params, Particles<D> particles);

  /// Advances by dt in equal substeps no longer than `stable` (stable_step() of the current state,
  /// when the caller has it already); returns the substep count.
  int advance(double dt, double stable);
  int advance(double dt) { return advance(dt, stable_step()); }
  /// One MPM step of size dt: stresses, particle-to-grid, grid update and exchange, grid-to-particle
  /// with the deformation update and the return mapping.
  void substep(double dt);
  /// cfl h / (c + max |v_p|), c the fastest wave speed of the phases present: the larger of the
  /// sand's √((λ + 2μ)/ρ_s) and the water's sound speed c_w; with sand that moves in a mixture, the
  /// bound √(c_s² + mixture_wave_factor c_w²) of the coupled waves (exchange.hpp).
  double stable_step() const;

  double time() const { return time_; }
  const Particles<D>& particles() const { return ps_; }
  const Params<D>& params() const { return params_; }
  const Nodes<D>& nodes() const { return nodes_; }
  /// Both phases are present: the pore pressure couples them.
  bool mixture() const { return mixture_; }
  const StageClock<MpmStage>& timers() const { return timers_; }
  StageClock<MpmStage>& timers() { return timers_; }
  /// The Kirchhoff stress of particle i now (Hencky for sand, the equation of state for water).
  Mat<D> kirchhoff(std::size_t i) const;
  /// The cohesion of sand particle i at its saturation.
  double cohesion(std::size_t i) const;

 private:
  void affine_momenta(double dt);
  void gather(double dt);
  void update_grid(double dt);
  void exchange(double dt);
  void scatter(double dt);
  void plasticity(std::size_t i);
  void apply_walls(const std::array<long, D>& node, bool sand, Vec<D>& v) const;
  bool clamped(const Vec<D>& x) const;

  Params<D> params_;
  Particles<D> ps_;
  Nodes<D> nodes_;
  std::vector<std::size_t> sand_, water_;  // particle indices of each phase, in order
  std::vector<std::uint8_t> clamped_;       // per node: 1 where a clamp holds the sand
  bool mixture_ = false;                    // both phases present: the pore pressure couples them
  bool loaded_ = false;                     // some particle carries a load
  bool free_sand_ = false;                  // some sand particle lies outside every clamp
  bool transferred_ = false;                // a grid-to-particle transfer has set the water's porosity
  Bins sand_bins_, water_bins_;
  std::vector<Mat<D>> affine_;              // m C − Δt V0 D⁻¹ τ of each particle
  std::vector<AxisWeights<D>> weights_;     // each particle's 1-D weights at its position of this substep
  std::vector<Mat<D>> tau_;                 // the sand's τ at its F^E, from the return mapping's SVD
  StageClock<MpmStage> timers_;
  double time_ = 0.0;
};

}  // namespace sc::mpm
