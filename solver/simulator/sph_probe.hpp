// The SPH probe: what only SPH can tell about a run, for the measurements that need it (the
// dam-break front's neighbour filter, the pond depth counted in full water particles, rigid
// cluster numbers, split-and-merge counts). Everything else is measured through the method-neutral
// ParticleView (method/method.hpp). This header does not include the simulator's: a caller sees
// the few quantities below, not SPH's internals.
#pragma once
#include <optional>
#include <string_view>

#include "adaptive/adaptivity.hpp"
#include "core/particle_set.hpp"
#include "case/case_file.hpp"
#include "method/method.hpp"
#include "neighbours/neighbour_grid.hpp"
#include "parallel/decomposition.hpp"

namespace sc {

template <int D>
class SphMethod;

/// Throws InputError (the case file, JSON path /method) unless the case runs with SPH: `who`
/// (an observer, a report) needs what only SPH provides. Called before anything is allocated.
void require_sph(const CaseSpec& spec, std::string_view who);

template <int D>
class SphProbe {
 public:
  explicit SphProbe(const SphMethod<D>& method) : method_(method) {}
  /// Every field of SPH's particles (same order as the run's ParticleView: decomposed over MPI
  /// ranks, every rank's gathered in the one-process order; collective then).
  const ParticleSet<D>& particles() const;
  /// The neighbour lists of the last step (empty before the first step).
  const NeighbourGrid<D>& neighbours() const;
  /// Mass of a full water particle at the run's spacing in a porous case (the lattice mass whose
  /// summation density is the rest density), against which lighter parcels of absorbed and
  /// emitted water are counted.
  double full_water_mass() const;
  /// What split and merge did so far (zero without an "adaptive" section).
  const AdaptAccount& adapt_account() const;
  /// What the decomposition over MPI ranks did, summed over the ranks (collective: every rank
  /// calls it); nullopt in one process.
  std::optional<DecompositionAccount> decomposition() const;

 private:
  const SphMethod<D>& method_;
};

/// The SPH probe of `method`. Throws std::logic_error naming `who` if the run does not use SPH
/// (a caller that needs it checks the case with require_sph first).
template <int D>
SphProbe<D> require_sph(const Method<D>& method, std::string_view who);

}  // namespace sc
