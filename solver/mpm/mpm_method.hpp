// Two-grid MPM after Tampubolon et al. 2017 behind the method seam: MpmMethod<D> runs an
// MpmSolver<D> (this folder) as a Method<D>, built from a case's blocks, tank, gravity, water and
// sand sections, with MPM's own numbers from the case's "methods": {"mpm": {...}} object
// (cases/README.md, docs/equations.md §9).
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "case/case_file.hpp"
#include "method/adapter.hpp"
#include "mpm/mpm_solver.hpp"

namespace sc {

/// MPM's own parameters of a case, "methods"/"mpm" (every key optional; with a "porous" section the
/// porosity and the conductivity are the section's, n = porosity and K = k ρ g / μ, and not keys here):
///   cell_size               grid cell width in particle spacings (2: 2^D particles per cell)
///   cfl                     substeps move the fastest wave at most cfl cell widths, in (0, 1]
///   youngs_modulus          E of the sand's Hencky elasticity [Pa]
///   poisson_ratio           ν of the sand, in [0, 0.5)
///   volume_correction       Tampubolon et al.'s volume correction of the return mapping (true)
///   porosity                n of the sand, in (0, 1)
///   hydraulic_conductivity  K [m/s] of the sand; the drag c_E = n² ρ_w g / K
///   without_capillarity     run a case whose porous section has capillary suction without it (false):
///                           MPM has none, its water enters the pores by gravity against the drag only
struct MpmCaseParams {
  double cell_size = 2.0;
  double cfl = 0.4;
  double youngs_modulus = 3.537e5;
  double poisson_ratio = 0.3;
  bool volume_correction = true;
  bool without_capillarity = false;
  double porosity = 0.4;
  double hydraulic_conductivity = 1e-3;
  double initial_saturation = 0.0;  ///< of a porous bed's pores ("porous"/"initial_saturation")
};

/// Reads and checks the case's "methods"/"mpm" object and that the case is one MPM can run (a tank,
/// blocks of water, sand or porous bed, no meshes or adaptivity, no capillarity in a porous section unless
/// `without_capillarity`, a
/// positive friction angle for sand). Throws InputError (the case file, the JSON path, the rule).
/// Allocates nothing.
MpmCaseParams read_mpm_params(const CaseSpec& spec);

/// The solver parameters of the case at particle spacing dx: the grid covers the tank, extended to
/// the domain on open sides (where a smooth lid at the grid's edge keeps the material in); each porous
/// bed is held by a clamp over the nodes its particles reach (its box grown by 1.5 cells).
template <int D>
mpm::Params<D> mpm_params(const CaseSpec& spec, const MpmCaseParams& own, double dx);

template <int D>
class MpmMethod final : public ParticleAdapter<D, mpm::Particles<D>> {
 public:
  /// The solver, the case's step (divided into stable substeps), the support radius the view reports
  /// and which particles are a porous bed's sand (1), shown as SPH shows its bed.
  MpmMethod(mpm::MpmSolver<D> solver, double dt, double support, std::vector<std::uint8_t> bed);

  std::string_view name() const override { return "mpm"; }
  /// Keeps the particles as the last good state, then advances the case's step in substeps. Throws
  /// BlowUpError (core/errors.hpp collapsed_step), before any substep, where the stable substep is
  /// below kShortestStepFraction of the case's step.
  double step() override;
  double time() const override { return solver_.time(); }
  long steps() const override { return steps_; }
  /// x, v, m, phase; pressure −tr τ / (D J) (water: the equation of state at J), seen through the
  /// grid (mpm/grid_field.hpp); density m / (J V0); the case's support radius; the sand's saturation
  /// (0 for water). Sand with water present is porous sand, with its porosity n, pore volume n J V0
  /// and pore-water pressure; a porous bed's sand is shown as a fixed porous phase (Phase::Boundary).
  /// The pore water is free water particles, so no water is held.
  ParticleView<D> particles() const override { return view_of(solver_.particles()); }
  /// The solver's stage times; the transfer's count is its substeps.
  std::vector<StageTime> stage_times() const override {
    return stage_times_of(mpm::mpm_stage_names, solver_.timers(), mpm::MpmStage::Transfer, substeps_);
  }
  void reset_stage_times() override {
    solver_.timers().reset();
    substeps_ = 0;
  }
  std::optional<long> own_steps() const override { return substeps_; }

  const mpm::MpmSolver<D>& solver() const { return solver_; }

 private:
  const mpm::Particles<D>& state() const override { return solver_.particles(); }
  ParticleView<D> view_of(const mpm::Particles<D>& ps) const override;
  void check_state() const;
  /// Whether particle i is sand with pores the view reports: a porous bed's, or any with water present.
  bool porous_sand(const mpm::Particles<D>& ps, std::size_t i) const { return bed_[i] || (solver_.mixture() && ps.is_sand(i)); }

  mpm::MpmSolver<D> solver_;
  double dt_, support_;
  std::vector<std::uint8_t> bed_;
  long steps_ = 0, substeps_ = 0;
  // fields of the last particles() call
  mutable std::vector<double> pressure_, density_, support_field_, porosity_, pore_volume_, pore_pressure_;
  mutable std::vector<std::uint8_t> phase_;
};

/// MPM at t = 0: the case's blocks on the lattice of spacing dx, in file order, at rest; each
/// particle carries ρ dx^D of its phase. A porous bed is sand (`sand.rest_density`) with water at the
/// same sites filling the share S0 of its pores: ρ_w n S0 dx^D, volume n S0 dx^D, porosity n.
template <int D>
std::unique_ptr<Method<D>> make_mpm_method(const CaseSpec& spec, double dx);

}  // namespace sc
