// SPH behind the method seam: SphMethod<D> runs a Simulator<D> (this folder) as a Method<D>, so
// the runner, the bench, checkpoints and the observers see SPH like any other method.
// What only SPH has (neighbour lists, porous parameters, cluster numbers, split-and-merge counts)
// is reached through sph_probe.hpp, never through Method<D>.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "io/checkpoint.hpp"
#include "method/method.hpp"
#include "simulator/simulator.hpp"

namespace sc {

template <int D>
class SphMethod final : public Method<D> {
 public:
  /// Runs `sim`, a run of the case whose parameters hash is `parameters_hash` at `spacing` (what
  /// its checkpoints are stamped with).
  SphMethod(Simulator<D> sim, std::string parameters_hash, double spacing);

  std::string_view name() const override { return "sph"; }
  double step() override { return sim_.step(); }
  double time() const override { return sim_.time(); }
  long steps() const override { return sim_.steps(); }
  ParticleView<D> particles() const override;
  std::string checksum() const override { return state().checksum(); }
  std::vector<StageTime> stage_times() const override;
  void reset_stage_times() override { sim_.timers().reset(); }
  std::string vtu_frame() const override;
  std::string last_good_frame() const override;
  bool writes_checkpoints() const override { return true; }
  void write_checkpoint(const std::string& path, const json& run) const override;

  /// The simulator itself, for the SPH probe (sph_probe.hpp) and SPH's own tests.
  const Simulator<D>& simulator() const { return sim_; }
  /// Every particle of the run, in the one-process order: the simulator's own or, decomposed over
  /// MPI ranks, gathered from every rank (collective; kept until the particles change).
  const ParticleSet<D>& state() const;

 private:
  mutable ParticleSet<D> gathered_;
  mutable long gathered_revision_ = -1;
  Simulator<D> sim_;
  std::string parameters_hash_;
  double spacing_;
  mutable std::vector<double> pore_water_pressure_;  // P^p − P^c of the last particles() call
  mutable std::vector<double> pore_volume_;          // φ V (porous_volume) of the last particles() call
};

/// SPH at t = 0: the case's scene at spacing dx. Throws InputError when an initial particle lies
/// outside the domain.
template <int D>
std::unique_ptr<Method<D>> make_sph_method(const CaseSpec& spec, double dx);

/// SPH continuing from a checkpoint of the same case and spacing (checked by the caller).
template <int D>
std::unique_ptr<Method<D>> resume_sph_method(const CaseSpec& spec, double dx, const Checkpoint& checkpoint);

/// make_sph_method and resume_sph_method with the scene decomposed over the MPI ranks of the run
/// (parallel/decomposition.hpp; the registry checks the case first, check_decomposable): every
/// rank calls them with the same case; the run is bitwise the one-process run, and what the method shows (particles, checksum,
/// frames, checkpoints) is the whole scene in the one-process order, gathered on every rank.
template <int D>
std::unique_ptr<Method<D>> make_decomposed_sph_method(const CaseSpec& spec, double dx);
template <int D>
std::unique_ptr<Method<D>> resume_decomposed_sph_method(const CaseSpec& spec, double dx, const Checkpoint& checkpoint);

}  // namespace sc
