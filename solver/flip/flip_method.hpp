// Zhu & Bridson 2005 PIC/FLIP behind the method seam: FlipMethod<D> runs a FlipSolver<D> (this
// folder) as a Method<D>, built from a case's blocks, tank, gravity and sand, with FLIP's own
// numbers from the case's "methods": {"flip": {...}} object (cases/README.md).
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "flip/flip_solver.hpp"
#include "case/case_file.hpp"
#include "method/adapter.hpp"

namespace sc {

/// FLIP's own parameters of a case, "methods"/"flip" (every key optional):
///   cell_size           grid cell width in particle spacings (2: 2^D particles per cell, the paper's)
///   flip_ratio          FLIP share of water's velocity update, in [0, 1] (sand is always PIC)
///   cfl                 particles move at most cfl cell widths per step
///   cg_tolerance        relative residual of the pressure solve
///   cg_max_iterations   iteration cap of the pressure solve
///   jitter              random offset of the seeded particles, in particle spacings, in [0, 1]
struct FlipCaseParams {
  double cell_size = 2.0;
  double flip_ratio = 0.95;
  double cfl = 1.0;
  double cg_tolerance = 1e-12;
  long cg_max_iterations = 2000;
  double jitter = 0.5;
};

/// Reads and checks the case's "methods"/"flip" object and that the case is one FLIP can run (a
/// tank, blocks of water or sand only, no meshes, porous flow or adaptivity). Throws InputError
/// (the case file, the JSON path, the rule). Allocates nothing.
FlipCaseParams read_flip_params(const CaseSpec& spec);

/// The solver parameters of the case at particle spacing dx: the grid covers the tank, extended
/// to the domain on open sides (whose outer faces stay solid, a lid far from the material).
/// Throws InputError when a closed extent of the tank is not a whole number of cells.
template <int D>
flip::FlipParams<D> flip_params(const CaseSpec& spec, const FlipCaseParams& own, double dx);

template <int D>
class FlipMethod final : public ParticleAdapter<D, flip::FlipParticles<D>> {
 public:
  explicit FlipMethod(flip::FlipSolver<D> solver);

  std::string_view name() const override { return "flip"; }
  /// Keeps the particles as the last good state, then steps the solver.
  double step() override;
  double time() const override { return solver_.time(); }
  long steps() const override { return solver_.steps(); }
  /// x, v, m, phase; the pressure interpolated from the cell centres; the density of the
  /// particle's phase (the grid is incompressible); the support of the transfer kernel (Δx).
  ParticleView<D> particles() const override;
  /// The solver's stage times; the projection's count is its CG iterations.
  std::vector<StageTime> stage_times() const override {
    return stage_times_of(flip::flip_stage_names, solver_.timers(), flip::FlipStage::Projection, projection_iterations_);
  }
  void reset_stage_times() override {
    solver_.timers().reset();
    projection_iterations_ = 0;
  }

  const flip::FlipSolver<D>& solver() const { return solver_; }

 private:
  const flip::FlipParticles<D>& state() const override { return solver_.particles(); }
  /// x, v, m and phase: the fields of the last good frame, and those particles() adds to.
  ParticleView<D> view_of(const flip::FlipParticles<D>& ps) const override;

  flip::FlipSolver<D> solver_;
  long projection_iterations_ = 0;  // CG iterations since the last reset_stage_times
  mutable std::vector<double> pressure_, density_, support_;  // fields of the last particles() call
};

/// FLIP at t = 0: the case's blocks seeded on the lattice of spacing dx (jittered), in file order.
template <int D>
std::unique_ptr<Method<D>> make_flip_method(const CaseSpec& spec, double dx);

}  // namespace sc
