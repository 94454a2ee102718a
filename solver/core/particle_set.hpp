// ParticleSet: every particle of a scene (water, sand, boundary) as a structure of arrays.
//
// Every per-particle field is declared once, in `visit_fields`, which the generic operations
// (append, compaction, permutation, VTU output, checksums) walk. To add a field, add the member
// and one line in `visit_fields`; nothing else needs to change.
//
// Deletions and creations are queued during a step (`queue_remove`, `additions()`) and applied by
// `compact()` at its end: removals in index order, then additions in the order they were queued,
// so the result does not depend on thread scheduling as long as additions are queued serially.
#pragma once
#include <cmath>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "core/types.hpp"

namespace sc {

/// The size of a particle of volume `volume` [m]: the edge V^(1/D) of the cube (square in 2-D) it
/// fills in a lattice. The one name for a size derived from a volume: adaptive sampling's split and
/// merge decisions (the rest volume of a particle's level) and porous flow's spacing (porous_spacing).
template <int D>
double particle_size(double volume) {
  return std::pow(volume, 1.0 / D);
}

template <int D>
class ParticleSet {
 public:
  using V = Vec<D>;
  using VecArray = std::vector<V, Eigen::aligned_allocator<V>>;

  // --- kinematics and SPH state -------------------------------------------------------------
  VecArray x;                   ///< position [m]
  VecArray v;                   ///< velocity [m/s]
  VecArray force;               ///< total force of the current step [N]
  std::vector<double> m;        ///< mass [kg]
  std::vector<double> h;        ///< kernel support radius [m]
  std::vector<double> rho;      ///< density [kg/m^3] (eq 6)
  std::vector<double> rho0;     ///< rest density [kg/m^3]
  std::vector<double> p;        ///< pressure [Pa] (eq 7 or linear state equation)
  std::vector<std::uint8_t> phase;   ///< Phase as an integer (VTU-friendly)
  std::vector<std::uint8_t> rough;   ///< boundary particles: 1 = no-slip (rough) wall, 0 = slip
  std::vector<std::int64_t> id;      ///< stable identity, never reused within a run
  std::vector<double> density_offset;  ///< adaptive runs: decaying density blend [kg/m^3] (adaptive/density_blend.hpp)
  /// Adaptive sampling level: 0 as the scene samples the particle, +1 per merge, −1 per split, so a
  /// full particle of level L has 2^L times the mass of a level-0 one (adaptive/split_merge.hpp).
  /// Kept, not derived from m/ρ0: porous flow changes both of a water particle it drains or fills.
  std::vector<std::uint8_t> level;
  // --- sand (solver/sand/) ----------------------------------------------------------------
  std::vector<std::uint8_t> rigid;   ///< sand: 1 = does not yield (eq 10), 0 = flowing
  std::vector<std::int32_t> cluster; ///< sand: rigid cluster number + 1 of this step, 0 = none
  std::vector<double> strain_rate;   ///< sand: |D|_F [1/s] (eq 9)
  // --- porous flow (solver/porous/): held only when has_porous_fields(), else empty -----------
  std::vector<double> absorbed;      ///< porous: absorbed water m_p [kg] (eq 21)
  std::vector<double> emit_store;    ///< porous: absorbed water waiting to leave as a new water particle [kg]
  std::vector<double> saturation;    ///< porous: S (eq 21)
  std::vector<double> porosity;      ///< porous: φ (eq 24); 0 for particles that are not porous
  std::vector<double> capillary;     ///< porous: capillary potential P^c [Pa] (eq 23)
  std::vector<double> pore_pressure; ///< porous: P^p [Pa] (eq 25)
  VecArray pore_velocity;            ///< porous and water taking part in the exchange: v_p [m/s] (eq 27)

  template <class F>
  void visit_fields(F&& f) {
    f("position", x); f("velocity", v); f("force", force);
    f("mass", m); f("support_radius", h); f("density", rho); f("rest_density", rho0);
    f("pressure", p); f("phase", phase); f("rough", rough); f("id", id); f("density_offset", density_offset);
    f("level", level);
    f("rigid", rigid); f("cluster", cluster); f("strain_rate", strain_rate);
    if (!porous_fields_) return;
    f("absorbed_water", absorbed); f("emit_store", emit_store); f("saturation", saturation);
    f("porosity", porosity); f("capillary_potential", capillary); f("pore_pressure", pore_pressure);
    f("pore_velocity", pore_velocity);
  }
  template <class F>
  void visit_fields(F&& f) const { const_cast<ParticleSet*>(this)->visit_fields(f); }

  std::size_t size() const { return x.size(); }
  /// Whether the set holds the porous-flow fields (absorbed ... pore_velocity). Only scenes with
  /// porous flow do (scene/scene_builder.cpp); elsewhere the fields stay empty and visit_fields
  /// leaves them out, so a water or dry-sand scene does not carry (twice, with the blow-up guard's
  /// copy) seven fields that are zero for every particle.
  bool has_porous_fields() const { return porous_fields_; }
  /// Holds the porous-flow fields from now on, zero for every particle already in the set.
  void add_porous_fields();
  /// Porosity φ of particle i (eq 24): 0 in a set without porous fields.
  double porosity_of(std::size_t i) const { return porous_fields_ ? porosity[i] : 0.0; }
  /// Saturation S of particle i (eq 21): 0 in a set without porous fields.
  double saturation_of(std::size_t i) const { return porous_fields_ ? saturation[i] : 0.0; }
  Phase phase_of(std::size_t i) const { return static_cast<Phase>(phase[i]); }
  bool moves(std::size_t i) const { return phase_of(i) != Phase::Boundary; }
  /// A fixed wall particle outside the porous flow: it only acts with moving or porous particles,
  /// so the neighbour search leaves out pairs of two inert particles.
  bool inert(std::size_t i) const { return phase_of(i) == Phase::Boundary && !(porosity_of(i) > 0.0); }
  double volume(std::size_t i) const { return m[i] / rho[i]; }

  /// Appends one particle with every field zero (rest density and density 1 to keep V finite)
  /// and a fresh id; returns its index.
  std::size_t append();

  /// Queues particle i for deletion at the next compact().
  void queue_remove(std::size_t i);
  /// Particles to be created at the next compact(); fill them with additions().append().
  ParticleSet& additions();
  /// Whether particle i is queued for deletion at the next compact().
  bool queued_for_removal(std::size_t i) const { return remove_flag_.size() == size() && remove_flag_[i] != 0; }
  /// How many particles are queued for creation at the next compact().
  std::size_t queued_additions() const { return additions_.empty() ? 0 : additions_.front().size(); }
  /// Applies queued removals (index order) and additions (queue order). Returns true if the
  /// particle set changed (neighbour lists must then be rebuilt).
  bool compact();
  /// Reorders every field: new index k holds old particle order[k].
  void permute(const std::vector<std::size_t>& order);
  /// Removes the particles from index n on (the halo a decomposed run appends after its own
  /// particles, parallel/decomposition.hpp), keeping the others where they are. When the last
  /// change of the layout appended particles after the first n, the set gets back the layout it
  /// had with the n alone: a rank's own particles keep their layout through a step, and the
  /// blow-up guard refreshes its copy instead of copying it (Simulator::save_last_good).
  void truncate(std::size_t n);
  /// Makes this a copy of `other` (as operator=, reusing this set's storage), copying the fields in
  /// parallel: the blow-up guard copies the state every step.
  void copy_from(const ParticleSet& other);
  /// copy_from for a set that already holds `other`'s values except for the density and pressure of
  /// its inert particles (inert() in both sets), and has its layout (layout()): copies the other
  /// particles in full and those two fields of the inert ones. A step changes nothing else of a
  /// fixed wall particle (its density offset stays 0: adaptive/density_blend.hpp sets only moving
  /// particles'), and walls are most of a tank scene's particles.
  void refresh_from(const ParticleSet& other);
  /// Changes whenever the particles are reordered, removed or added (permute, compact, append,
  /// truncate) to a value no other order of particles in the process has had.
  std::uint64_t layout() const { return layout_; }
  /// Bytes of all positions and velocities hashed (FNV-1a 64), as 16 hex digits.
  std::string checksum() const;

  std::int64_t next_id() const { return next_id_; }
  void set_next_id(std::int64_t n) { next_id_ = n; }

 private:
  /// Calls f(field, other's field of the same name) for every field.
  template <class F>
  void visit_fields_with(const ParticleSet& other, F&& f);

  /// The first particles in their order before the particles after them were appended.
  struct Prefix {
    std::size_t size;
    std::uint64_t layout;
  };
  /// A new layout after a change other than appending.
  void relayout();
  /// A new layout after appending to the first `before.size` particles, which had `before.layout`.
  void appended(Prefix before);

  std::vector<std::uint8_t> remove_flag_;
  std::vector<ParticleSet> additions_;  // zero or one element (a class cannot hold itself)
  std::int64_t next_id_ = 0;
  std::uint64_t layout_ = 0;
  bool porous_fields_ = false;
  std::optional<Prefix> prefix_;  // set when the last change of the layout was an append
};

std::string_view phase_name(Phase p);

}  // namespace sc
