#include "porous/porous_flow.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "porous/capillary.hpp"
#include "porous/darcy.hpp"
#include "porous/diffusion.hpp"
#include "porous/partial_water_pressure.hpp"
#include "porous/pore_pressure.hpp"
#include "porous/porous_volume.hpp"
#include "porous/rigid_pore_pressure.hpp"
#include "porous/saturation.hpp"
#include "porous/wet_density.hpp"

namespace sc {

namespace {

constexpr double kPlacementGap = 0.8;  // new water particles: no particle closer than this many spacings
constexpr double kContactDistance = 1.5;  // spacings: a porous particle this close to water touches it
constexpr double kSaturated = 0.99;    // a fixed porous particle with S at least this holds pore-water pressure

template <int D>
bool porous_at(const ParticleSet<D>& ps, std::size_t i) { return is_porous_phase(ps.phase_of(i), ps.porosity[i]); }

/// Decomposed (`ranks`): overwrites the halo's entries of each of `fields` with their owners' values,
/// before a pass that reads them from neighbours.
template <int D, class... Fields>
void refresh(const Decomposition<D>* ranks, Fields&... fields) {
  if (ranks) (ranks->refresh(fields), ...);
}

/// The place of particle i in the one-process storage: its index, or its key when decomposed.
template <int D>
std::uint64_t place(const Decomposition<D>* ranks, std::size_t i) {
  return ranks ? ranks->key(i) : static_cast<std::uint64_t>(i);
}

/// Whether particle i is one of this process's own (not a halo copy).
template <int D>
bool own(const Decomposition<D>* ranks, std::size_t i) {
  return !ranks || !ranks->is_halo(i);
}

/// Which particles are porous (porous_at), from the porosity at the start of the step (fill_slot
/// updates it for moving sand).
template <int D>
void mark_porous(const ParticleSet<D>& ps, PorousWork<D>& w) {
  const auto n = static_cast<std::int64_t>(ps.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) w.porous[i] = porous_at(ps, i);
}

/// Porous particles and water particles with a porous neighbour take part; porous particles with
/// a water neighbour closer than kContactDistance spacings are in contact with free water (the
/// body's surface row, not the row under it). Other particles (non-porous walls and sand) have
/// neither mark and skip the scan. Keeps the spacing of porous particles for the later passes.
template <int D>
void mark_participant(const ParticleSet<D>& ps, const NeighbourGrid<D>& nb, const PorousParams& p, PorousWork<D>& w,
                      std::size_t i) {
  const auto list = nb.of(i);
  bool near = false, touches = false;
  w.spacing[i] = w.porous[i] ? porous_spacing(ps, i, p) : 0.0;
  if (ps.phase_of(i) == Phase::Water) {
    near = std::any_of(list.begin(), list.end(), [&](std::uint32_t j) { return w.porous[j] != 0; });
  } else if (w.porous[i]) {
    const double reach = kContactDistance * w.spacing[i];
    touches = std::any_of(list.begin(), list.end(), [&](std::uint32_t j) {
      return ps.phase_of(j) == Phase::Water && (ps.x[j] - ps.x[i]).norm() < reach;
    });
  }
  w.part[i] = w.porous[i] || near;
  w.contact[i] = w.porous[i] && touches;
}

/// Pore-water pressure of fixed (rigid) porous particles, ours [I]. Eq 25 answers only to skeleton
/// compression, so a rigid skeleton would have P^p = 0 and, with S <= 1 capping the content,
/// Darcy flow through it would be driven by gravity alone (q = K whatever the pond depth). In a
/// rigid saturated skeleton the pore water is incompressible and its pressure is what keeps the
/// flow divergence-free (solve_harmonic_pressure). The conditions:
/// - in contact with free water (a water neighbour): pore-water pressure P^p − P^c = the pond's
///   pressure (set_contact_pressure);
/// - at a seepage face or a top open to the air (empty space below, above or along v_p,
///   exposure): P^p = 0, the atmosphere's;
/// - unsaturated: P^p = 0, the pore water being at the capillary suction −P^c (eq 23);
/// - moving (deformable) sand: Lenaerts' eq 25;
/// - saturated, fixed, none of the above: harmonic, solved.
/// Saturated means that the particle held at least kSaturated of its pores' capacity while it
/// passed this step's outflow on: m_p after the step plus that outflow, i.e. m_p before it plus the
/// step's inflow. A particle in the wet zone of a flow passes |v_p| Δt / dx of its pores per step,
/// and the explicit limited update (eqs 28′-30) leaves it about that much short of full at the
/// end of the step. Counted by its content after the step, the wet zone would turn "unsaturated"
/// wherever |v_p| Δt / dx exceeds 1 − kSaturated, its pressure would be set to 0 there and the
/// pond's pressure would not reach the front, an error that grows with refinement at a fixed step
/// (test porous/a_fast_flow_keeps_the_wet_zone_under_the_pond_pressure). A draining particle still
/// turns unsaturated: its inflow does not make up what it loses.
template <int D>
PressureRole pressure_role(const ParticleSet<D>& ps, const PorousWork<D>& w, std::size_t i) {
  if (!w.porous[i]) return PressureRole::None;
  const bool saturated = ps.absorbed[i] + ps.emit_store[i] + w.passed[i] >= kSaturated * w.slot[i].capacity;
  const bool solved = ps.phase_of(i) == Phase::Boundary && !w.contact[i] && !w.seepage[i] && saturated;
  return solved ? PressureRole::Unknown : PressureRole::Prescribed;
}

/// Pore water that moving sand squeezed out: when the sand compressed since the last step (its
/// pore volume φ V falls with the density, eq 24) and m_p exceeds the pores' capacity ρ^f φ V, the
/// excess moves to the emission store (given to neighbouring water or emitted as new particles like
/// any emitted water), so that the raw saturation m_p/(ρ^f φ V) never exceeds 1 and free + stored +
/// absorbed water is unchanged. Ours: the limiters of eq 30 keep S <= 1 only for a fixed volume.
template <int D>
void squeeze_out(ParticleSet<D>& ps, std::size_t i, double capacity) {
  const double excess = ps.absorbed[i] - capacity;
  if (excess <= 0.0) return;
  ps.absorbed[i] = capacity;
  ps.emit_store[i] += excess;
}

/// A water particle is overfull when its summation density (eq 6) exceeds its rest density by more
/// than this fraction: well beyond the compression of weakly compressible water at rest (about 1 %,
/// by the choice of the sound speed), so its neighbours are closer than the lattice spacing.
constexpr double kOverfullCompression = 0.05;

/// Whether water particle i is overfull (kOverfullCompression); ours [I]. An overfull particle has
/// no room for water from porous neighbours: what it took would go into a place already more than
/// filled, raising the pressure of its own state equation as it refills. A parcel that drifted
/// into the face of a fixed bed sits among the bed's particles, closer than the spacing (tens of
/// percent above its rest density), and refilled there it was thrown out with the pond above it
/// (darcy_column; test porous/a_compressed_water_particle_takes_no_water_from_the_bed). It still
/// gives water, so the bed takes it in.
template <int D>
bool overfull(const ParticleSet<D>& ps, std::size_t i) {
  return ps.rho[i] > (1.0 + kOverfullCompression) * ps.rho0[i];
}

/// Saturation (eq 21), porosity (eq 24), capillary potential (eq 23) and pore pressure (eq 25)
/// of porous particle i; the saturated-porous view of a water particle (room up to a full
/// particle's mass, none when overfull).
template <int D>
void fill_slot(ParticleSet<D>& ps, const PorousParams& p, const Vec<D>& g, double dt, PorousWork<D>& w, std::size_t i) {
  const double rho_f = p.fluid_density;
  if (!w.part[i]) return;
  ExchangeSlot<D>& s = w.slot[i];
  s = ExchangeSlot<D>{};
  s.x = ps.x[i];
  s.h = ps.h[i];
  s.height = g.norm() > 0.0 ? -ps.x[i].dot(g) / g.norm() : 0.0;
  if (!w.porous[i]) {
    w.pc[i] = 0.0;  // water in contact counts as saturated
    w.pp[i] = 0.0;
    const double full = full_mass_at_level(ps, i, p.water_mass);
    s.mass = ps.m[i];
    s.capacity = overfull(ps, i) ? std::min(full, ps.m[i]) : full;
    s.volume = full / rho_f;
    s.contact_speed = p.spacing / dt;
    s.flow_factor = ps.m[i] > 0.0 ? full / ps.m[i] : 0.0;  // gives as a full particle
    if (p.diffusion == PorousDiffusion::LenaertsLiteral) s.flow_factor = 1.0;  // Lenaerts' case B: S = 1, S^β = 1
    return;
  }
  const bool fixed = ps.phase_of(i) == Phase::Boundary;
  const double V = porous_volume(ps, i);
  if (carries_held_water(ps, i)) w.rest_volume[i] = V;
  ps.porosity[i] = fixed ? p.porosity : porosity(p.porosity, ps.rho0[i], ps.rho[i]);
  if (!fixed) squeeze_out(ps, i, rho_f * ps.porosity[i] * V);
  const double S = saturation(ps.absorbed[i], rho_f, ps.porosity[i], V);
  ps.saturation[i] = S;
  ps.capillary[i] = capillary_potential(S, p.capillary_constant, p.capillary_exponent);
  if (!fixed)
    ps.pore_pressure[i] = pore_pressure(p.pore_stiffness, S, ps.rho[i], ps.rho0[i], p.pore_gamma,
                                        p.thesis_pore_pressure_ratio);
  w.pc[i] = ps.capillary[i];
  w.pp[i] = ps.pore_pressure[i];
  s.mass = ps.absorbed[i];
  s.capacity = rho_f * ps.porosity[i] * V;
  s.flow_factor = std::pow(S, p.saturation_exponent);
  s.volume = V;
  s.draws_up = ps.capillary[i] > rho_f * g.norm() * w.spacing[i];
}

/// Marks the participants and fills their slots in one pass (each particle reads only the porous
/// marks of its neighbours, set before); returns whether a fixed porous particle touches water.
template <int D>
bool prepare_participants(ParticleSet<D>& ps, const NeighbourGrid<D>& nb, const PorousParams& p, const Vec<D>& g,
                          double dt, PorousWork<D>& w) {
  mark_porous(ps, w);
  const auto n = static_cast<std::int64_t>(ps.size());
  bool fixed_contact = false;
#pragma omp parallel for schedule(dynamic, 256) reduction(|| : fixed_contact)
  for (std::int64_t i = 0; i < n; ++i) {
    mark_participant(ps, nb, p, w, i);
    fill_slot(ps, p, g, dt, w, i);
    fixed_contact = fixed_contact || (w.contact[i] && ps.phase_of(i) == Phase::Boundary);
  }
  return fixed_contact;
}

/// The pond's pressure at fixed porous particles in contact with water (pressure_role): their
/// pore-water pressure P^p − P^c of [thesis eq. 27] is the pressure of the free water next to them
/// (pond_pressure: the weight of the water columns, carried to them hydrostatically), so
/// P^p = pond + P^c (P^c of [thesis eq. 23], with α = 0.1 still ~0.55 k^c at the S ≈ 0.997 a
/// flowing wet zone keeps). Giving P^p the pond's pressure alone took P^c off the pond's drive
/// at the surface.
template <int D>
void set_contact_pressure(ParticleSet<D>& ps, const NeighbourGrid<D>& nb, const PorousParams& p, const Vec<D>& g,
                          const PorousWork<D>& w, const Decomposition<D>* ranks) {
  const auto n = static_cast<std::int64_t>(ps.size());
  const std::vector<double> column = water_column_pressure(ps, p.spacing, p.water_mass, p.fluid_density, g.norm(), ranks);
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t i = 0; i < n; ++i)
    if (w.contact[i] && ps.phase_of(i) == Phase::Boundary)
      ps.pore_pressure[i] = pond_pressure(ps, nb, column, i, p.fluid_density, g) + ps.capillary[i];
  refresh(ranks, ps.pore_pressure);
}

/// Pore velocity (eq 27) of porous particles from the gradients (eq 22) of the capillary potential
/// (water in contact counts as saturated, P^c = 0) and of the pore pressure (over porous particles
/// only: the pond's pressure enters through the particles in contact). Water particles give by
/// contact (pair_flow) and have no pore velocity, except under the literal eq 28 (switch
/// "lenaerts_literal"), where they take part as Lenaerts' case B (Lenaerts 2008 §4.1): saturated
/// porous particles with φ = 1 and S = 1 in eqs 3-10, so eq 27 gives them a pore velocity too.
template <int D>
void pore_velocities(ParticleSet<D>& ps, const NeighbourGrid<D>& nb, const PorousParams& p, const Vec<D>& g,
                     PorousWork<D>& w) {
  const auto n = static_cast<std::int64_t>(ps.size());
  const bool capillary = p.capillary_constant != 0.0;
  const bool case_b = p.diffusion == PorousDiffusion::LenaertsLiteral;
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t i = 0; i < n; ++i) {
    if (!w.part[i]) continue;
    if (!w.porous[i] && !case_b) {
      ps.pore_velocity[i] = Vec<D>::Zero();
      continue;
    }
    const auto [grad_p, grad_c] = porous_gradients(ps, nb, w.pp, w.porous, w.pc, w.part, capillary, i, p.gradient);
    const double phi = w.porous[i] ? ps.porosity[i] : 1.0;
    ps.pore_velocity[i] = pore_velocity<D>(p.permeability, p.fluid_viscosity, phi, grad_p, grad_c, p.fluid_density, g);
    w.slot[i].pore_velocity = ps.pore_velocity[i];
  }
}

/// Which of the places of exposure are free: no particle of i's neighbourhood lies within
/// kPlacementGap spacings of it, counting the water particles as each says.
struct FreePlaces {
  bool below = true;           ///< one spacing below i (along g), counting no water
  bool above = true;           ///< one spacing above i (against g), and no water in i's neighbourhood
  bool target_solid = true;    ///< at the target, counting no water
  bool target_staying = true;  ///< at the target, counting the water not moving away along v_p
  bool target_all = true;      ///< at the target, counting all water
};

/// FreePlaces of i in one pass over its neighbours (`below`, `above` and `target` may be null: not
/// asked).
template <int D>
FreePlaces free_places(const ParticleSet<D>& ps, const NeighbourGrid<D>& nb, std::size_t i, const Vec<D>* below,
                       const Vec<D>* above, const Vec<D>* target, double s, const Vec<D>& away) {
  FreePlaces f;
  const double gap = kPlacementGap * s;
  for (const auto j : nb.of(i)) {
    const bool is_water = ps.phase_of(j) == Phase::Water;
    if (below && !is_water && !((ps.x[j] - *below).norm() >= gap)) f.below = false;
    if (above && (is_water || !((ps.x[j] - *above).norm() >= gap))) f.above = false;
    if (!target || (ps.x[j] - *target).norm() >= gap) continue;
    f.target_all = false;
    if (!is_water) f.target_solid = false;
    if (!is_water || ps.v[j].dot(away) <= 0.0) f.target_staying = false;
  }
  return f;
}

/// Seepage into empty space: the target one spacing along v_p and the flow a full half-space
/// of receivers would take there (zero when the suction holds the water or the place is occupied;
/// water there that moves away along v_p, such as the particle emitted in the previous steps,
/// does not stop the seepage: the store waits until the place is free, w.placeable). A particle
/// with a place one spacing along v_p or below it (along g) that holds no solid or porous particle
/// (water dripping there does not count) is on a seepage face (w.seepage: its pore-water pressure
/// is the atmosphere's, pressure_role), whatever v_p is now; so is one with a free place one
/// spacing above it (against g) and no water in its neighbourhood: its pores open to the air
/// there, which enters as the bed drains (a saturated bed without a pond drains at the Darcy flux,
/// test porous/a_saturated_bed_drains_at_the_darcy_flux; a no-flow top would hold its water up).
/// A pond within the support still covers it, though SPH holds the pond's bottom row off the
/// bed's top by more than the contact distance at times.
template <int D>
void exposure(const ParticleSet<D>& ps, const NeighbourGrid<D>& nb, const PorousParams& p, const Vec<D>& g,
              PorousWork<D>& w) {
  const auto n = static_cast<std::int64_t>(ps.size());
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t i = 0; i < n; ++i) {
    w.exposed[i] = 0;
    w.placeable[i] = 0;
    w.seepage[i] = 0;
    w.ghost[i] = 0.0;
    if (!w.porous[i]) continue;
    const double speed = ps.pore_velocity[i].norm();
    const double s = w.spacing[i];
    if (ps.capillary[i] > p.fluid_density * g.norm() * s) continue;
    const bool down = g.norm() > 0.0;
    const Vec<D> below = down ? Vec<D>(ps.x[i] + (s / g.norm()) * g) : ps.x[i];
    const Vec<D> above = down ? Vec<D>(ps.x[i] - (s / g.norm()) * g) : ps.x[i];
    if (speed > 0.0) w.target[i] = ps.x[i] + (s / speed) * ps.pore_velocity[i];
    const FreePlaces f = free_places(ps, nb, i, down ? &below : nullptr, down ? &above : nullptr,
                                     speed > 0.0 ? &w.target[i] : nullptr, s, ps.pore_velocity[i]);
    w.seepage[i] = down && (f.below || f.above);
    if (speed <= 0.0) continue;
    w.exposed[i] = f.target_staying;
    w.placeable[i] = w.exposed[i] && f.target_all;
    w.seepage[i] = w.seepage[i] || f.target_solid;
    if (w.exposed[i] && ps.absorbed[i] > 0.0) w.ghost[i] = w.slot[i].flow_factor * ps.absorbed[i] * speed / s;
  }
}

template <int D>
bool exchanges(const PorousWork<D>& w, std::size_t i, std::size_t j) {
  return j != i && w.part[j] && (w.porous[i] || w.porous[j]);
}

/// Particle i, of mass m_i and velocity v_i, receives the mass dm moving at u: its momentum
/// becomes m_i v_i + dm u, its velocity the mass-weighted mean (absorption of a whole water
/// particle, absorb_small).
template <int D>
void receive(double& m, Vec<D>& v, double dm, const Vec<D>& u) {
  v = (m * v + dm * u) / (m + dm);
  m += dm;
}

/// Momentum of the water exchanged in a step of diffusion (thesis §3.4: the absorbed water counts
/// in all computations): water a particle gives leaves at its velocity, which keeps it; water it
/// takes brings the giver's velocity, so a moving receiver i (mass m_i after the step, already
/// updated) gets v_i += (Σ_j Δm_j v_j − Δm v_i)/m_i, Δm = w.taken, Σ_j Δm_j v_j = w.brought, and
/// Σ m v of water and moving sand is unchanged (test
/// porous/absorption_and_emission_conserve_the_momentum_of_water_and_sand). A fixed porous bed
/// (velocity 0) neither moves nor counts: what it takes leaves the system with the support, what
/// it gives arrives at rest. A particle that takes nothing keeps its velocity bitwise. A water
/// particle left with no mass keeps its velocity. Its outflow limit (outflow_scale) lets it give
/// at most what it held, so its mass ends at exactly 0 only when what it took is below the
/// round-off of that mass; the momentum Σ_j Δm_j v_j − Δm v_i it cannot carry is of that order
/// and is dropped. A division by the zero mass would give an infinite velocity (0/0 when nothing
/// differs) that absorb_small hands on to the grain taking the empty particle.
template <int D>
void take_momentum(ParticleSet<D>& ps, const PorousWork<D>& w) {
  const auto n = static_cast<std::int64_t>(ps.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i)
    if (w.part[i] && ps.moves(i) && w.taken[i] > 0.0 && ps.m[i] > 0.0) ps.v[i] += (w.brought[i] - w.taken[i] * ps.v[i]) / ps.m[i];
}

/// Conserving diffusion (28′): raw flows (kept per neighbour-list entry), limiter scales,
/// limited update (eq 30). A particle whose raw flows are all zero (w.flowing[i] = 0: dry sand
/// with dry neighbours, most of a scene) skips its neighbours in the limiter passes: they would
/// only add +0 to its sums (sums that start at +0 or above), so the bits are the same.
template <int D>
void diffuse_conserving(ParticleSet<D>& ps, const NeighbourGrid<D>& nb, const PorousParams& p, double dt, PorousWork<D>& w,
                        const Decomposition<D>* ranks) {
  const auto n = static_cast<std::int64_t>(ps.size());
  w.to.resize(nb.total_pairs());
  w.from.resize(nb.total_pairs());
  std::vector<double>&to = w.to, &from = w.from;
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t i = 0; i < n; ++i) {
    w.a[i] = w.b[i] = 0.0;
    w.flowing[i] = 0;
    if (!w.part[i]) continue;
    double out = w.ghost[i], in = 0.0;
    bool flowing = false;
    std::size_t k = nb.list_start(i);
    for (const auto j : nb.of(i)) {
      const bool pair = exchanges(w, i, j);
      to[k] = pair ? pair_flow(w.slot[i], w.slot[j], p.flux_length_factor) : 0.0;
      from[k] = pair ? pair_flow(w.slot[j], w.slot[i], p.flux_length_factor) : 0.0;
      if (pair) {
        out += to[k];
        in += from[k];
        flowing = flowing || to[k] != 0.0 || from[k] != 0.0;
      }
      ++k;
    }
    w.flowing[i] = flowing;
    w.a[i] = outflow_scale(w.slot[i].mass, out, dt);
    w.b[i] = inflow_scale(w.slot[i].mass, w.slot[i].capacity, in, dt);
    w.in[i] = in;
  }
  refresh(ranks, w.a, w.b);  // the limits of the neighbours
  // Second inflow limit: the room also counts what the particle surely sends out in the step, its
  // outflow under the first limits (outflows only grow when the limits are relaxed, so the bound
  // m_p <= capacity still holds); without it a saturated particle in a steady flow stays short of
  // S = 1 by one step's inflow, which costs (β + 1) times that in relative permeability.
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t i = 0; i < n; ++i) {
    w.relaxed[i] = 0.0;
    if (!w.part[i]) continue;
    double out = w.ghost[i] * w.a[i];
    std::size_t k = nb.list_start(i);
    if (w.flowing[i])
      for (const auto j : nb.of(i)) out += to[k++] * std::min(w.a[i], w.b[j]);
    w.relaxed[i] = inflow_scale(w.slot[i].mass - dt * out, w.slot[i].capacity, w.in[i], dt);
  }
  w.b.swap(w.relaxed);
  refresh(ranks, w.b);
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t i = 0; i < n; ++i) {
    if (!w.part[i]) continue;
    double out = w.ghost[i] * w.a[i], in = 0.0, sent = 0.0;
    Vec<D> brought = Vec<D>::Zero();
    std::size_t k = nb.list_start(i);
    if (w.flowing[i])
      for (const auto j : nb.of(i)) {
        const double give = to[k] * std::min(w.a[i], w.b[j]), take = from[k] * std::min(w.a[j], w.b[i]);
        out += give;
        in += take;
        sent += give;
        brought += take * ps.v[j];
        ++k;
      }
    const double m = euler_mass(w.slot[i].mass, in, out, dt);
    w.passed[i] = dt * out;
    w.taken[i] = dt * in;
    w.brought[i] = dt * brought;
    if (w.porous[i]) {
      ps.absorbed[i] = m;
      ps.emit_store[i] += dt * w.ghost[i] * w.a[i];
      if (carries_held_water(ps, i)) ps.m[i] += dt * (in - sent);
    } else {
      ps.m[i] = m;
    }
  }
  take_momentum(ps, w);
  refresh(ranks, ps.absorbed, ps.emit_store, ps.m, ps.v);  // absorb_small's receivers
}

/// Capillary potential P^c [thesis eq. 23] that the next step's pore velocity will see at i: that of
/// the saturation after this step for fixed porous particles off the pond (fill_slot computes it so),
/// this step's for the others (the pond contact's P^p = pond + P^c was set with it). The suction of
/// solve_harmonic_pressure.
template <int D>
double suction_after_step(const ParticleSet<D>& ps, const PorousParams& p, const PorousWork<D>& w, std::size_t i) {
  if (!w.porous[i]) return 0.0;
  if (ps.phase_of(i) != Phase::Boundary || w.contact[i]) return ps.capillary[i];
  const double S = saturation(ps.absorbed[i], p.fluid_density, p.porosity, porous_volume(ps, i));
  return capillary_potential(S, p.capillary_constant, p.capillary_exponent);
}

/// Pore-water pressure of fixed porous particles for the next step (pressure_role): prescribed
/// values, then the saturated rigid zone solved for its pore-water pressure P^p − P^c.
template <int D>
void update_rigid_pore_pressure(ParticleSet<D>& ps, const NeighbourGrid<D>& nb, const PorousParams& p, const Vec<D>& g,
                                PorousWork<D>& w, const Decomposition<D>* ranks) {
  const auto n = static_cast<std::int64_t>(ps.size());
  w.role.resize(ps.size());
  bool unknowns = false;
#pragma omp parallel for schedule(static) reduction(|| : unknowns)
  for (std::int64_t i = 0; i < n; ++i) {
    w.role[i] = pressure_role(ps, w, i);
    unknowns = unknowns || w.role[i] == PressureRole::Unknown;
    if (w.role[i] == PressureRole::Prescribed && ps.phase_of(i) == Phase::Boundary && !w.contact[i])
      ps.pore_pressure[i] = 0.0;
  }
  if (!unknowns && !ranks) return;  // decomposed, every rank takes part in the solve (it may have none)
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) w.suction[i] = suction_after_step(ps, p, w, i);
  refresh(ranks, w.role, w.suction, ps.pore_pressure);
  solve_harmonic_pressure(ps, nb, w.role, w.suction, p.fluid_density, g, ps.pore_pressure, ranks);
}

/// The literal eq 28 (switch "lenaerts_literal"): each particle integrates its own rate and is
/// clamped to [0, capacity]; water is neither conserved nor emitted into empty space.
template <int D>
void diffuse_literal(ParticleSet<D>& ps, const NeighbourGrid<D>& nb, double dt, PorousWork<D>& w) {
  const auto n = static_cast<std::int64_t>(ps.size());
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t i = 0; i < n; ++i) {
    if (!w.part[i]) continue;
    double rate = 0.0;
    for (const auto j : nb.of(i))
      if (exchanges(w, i, j)) rate += literal_rate(w.slot[i], w.slot[j]);
    const double m = std::clamp(w.slot[i].mass + dt * rate, 0.0, w.slot[i].capacity);
    if (carries_held_water(ps, i)) ps.m[i] += m - ps.absorbed[i];
    (w.porous[i] ? ps.absorbed[i] : ps.m[i]) = m;
  }
}

/// Rest densities after the exchange: every water particle taking part, whose mass may differ from
/// that of a full particle at its level, gets partial_water_rest_density; moving porous sand, whose
/// mass holds its water, the wet rest density of [thesis eq. 31] at its rest volume of the start
/// of the step (set_wet_rest_density), and a density ρ scaled with it: the density sum counts
/// sand neighbours at ρ0_i/ρ0_j (sph/density.hpp), so ρ_i follows ρ0_i, and the volume m/ρ and
/// the compression ρ/ρ0 stay those the step used until the next density sum.
template <int D>
void update_rest_densities(ParticleSet<D>& ps, const PorousParams& p, const PorousWork<D>& w) {
  const auto n = static_cast<std::int64_t>(ps.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    if (carries_held_water(ps, i)) {
      const double before = ps.rho0[i];
      set_wet_rest_density(ps, i, w.rest_volume[i], p.porosity, p.fluid_density);
      ps.rho[i] *= ps.rho0[i] / before;
    } else if (w.part[i] && !w.porous[i])
      ps.rho0[i] = partial_water_rest_density(p.fluid_density, full_mass_at_level(ps, i, p.water_mass), ps.m[i],
                                              kernel::density_kernel<D>(p.density_kernel, 0.0, ps.h[i]));
  }
}

/// A porous neighbour a nearly empty water particle may give its rest to (absorb_small), as it is
/// before the absorptions of the step: its place in the one-process storage, capacity, content,
/// mass and velocity, and whether its mass holds its water (moving sand).
template <int D>
struct Receiver {
  std::uint64_t at;
  double capacity, absorbed, m;
  Vec<D> v;
  bool held;
};

/// A nearly empty water particle (absorb_small): its place, mass, velocity, and its receivers
/// [first, first + count) in neighbour-list order.
template <int D>
struct SmallWater {
  std::uint64_t at;
  double m;
  Vec<D> v;
  std::uint64_t first, count;
};

/// The buffers of absorb_small, kept by the thread between steps (no allocation in a step that
/// needs no more room than an earlier one).
template <int D>
struct SmallWaterBuffers {
  std::vector<SmallWater<D>> small;
  std::vector<Receiver<D>> receivers;
  std::vector<Receiver<D>> state;    // the receivers, each once, by place
  std::vector<std::size_t> mine;     // index of each of small (this rank's)
  std::vector<std::size_t> order;    // small by place
  std::vector<std::uint8_t> absorbed;  // by candidate
};

/// The receiver at place `at` among `state` (sorted by place, each once).
template <int D>
Receiver<D>& receiver_at(std::vector<Receiver<D>>& state, std::uint64_t at) {
  return *std::lower_bound(state.begin(), state.end(), at, [](const Receiver<D>& r, std::uint64_t a) { return r.at < a; });
}

/// Decides absorb_small in the one-process order (by place): each small water particle gives its
/// rest to the receiver with the most room as the earlier absorptions left it (the first in list
/// order among equals), if that has room for it. Leaves the receivers' states after it in
/// b.state (by place, each receiver once: its copies in several lists carry the same values) and
/// marks the absorbed particles in b.absorbed (by candidate).
template <int D>
void replay_absorption(SmallWaterBuffers<D>& b) {
  const auto by_place = [](const auto& x, const auto& y) { return x.at < y.at; };
  b.state.assign(b.receivers.begin(), b.receivers.end());
  std::sort(b.state.begin(), b.state.end(), by_place);
  b.state.erase(std::unique(b.state.begin(), b.state.end(), [](const auto& x, const auto& y) { return x.at == y.at; }),
                b.state.end());
  b.order.resize(b.small.size());
  std::iota(b.order.begin(), b.order.end(), std::size_t{0});
  std::sort(b.order.begin(), b.order.end(), [&](std::size_t x, std::size_t y) { return b.small[x].at < b.small[y].at; });
  b.absorbed.assign(b.small.size(), 0);
  for (const std::size_t c : b.order) {
    const SmallWater<D>& i = b.small[c];
    Receiver<D>* best = nullptr;
    double best_room = -1.0;
    for (std::uint64_t k = i.first; k < i.first + i.count; ++k) {
      Receiver<D>& r = receiver_at(b.state, b.receivers[k].at);
      const double room = r.capacity - r.absorbed;
      if (room > best_room) { best = &r; best_room = room; }
    }
    if (!best || best_room < i.m) continue;
    if (best->held) receive(best->m, best->v, i.m, i.v);
    best->absorbed += i.m;
    b.absorbed[c] = 1;
  }
}

/// Deletes water particles that are (nearly) empty, giving their rest, with its momentum, to the
/// porous neighbour with the most room (kept if none has room), one after the other in storage
/// order (replay_absorption). Decomposed, every rank's small particles and their receivers (with
/// the values refreshed in the halo) are gathered and every rank replays them all in key order;
/// each rank then writes the receivers it holds, own or halo, and removes its own absorbed ones.
template <int D>
std::size_t absorb_small(ParticleSet<D>& ps, const NeighbourGrid<D>& nb, const PorousParams& p, const PorousWork<D>& w,
                         const Decomposition<D>* ranks) {
  thread_local SmallWaterBuffers<D> b;
  b.small.clear();
  b.receivers.clear();
  b.mine.clear();
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (!own(ranks, i) || !w.part[i] || w.porous[i] || ps.m[i] >= p.min_water_fraction * full_mass_at_level(ps, i, p.water_mass))
      continue;
    SmallWater<D> c{place(ranks, i), ps.m[i], ps.v[i], b.receivers.size(), 0};
    for (const auto j : nb.of(i))
      if (w.porous[j]) b.receivers.push_back({place(ranks, j), w.slot[j].capacity, ps.absorbed[j], ps.m[j], ps.v[j], carries_held_water(ps, j)});
    c.count = b.receivers.size() - c.first;
    b.small.push_back(c);
    b.mine.push_back(i);
  }
  const std::size_t local = b.small.size();
  if (ranks) {
    // Each rank's candidates point into its own receivers: renumbered in the gathered order.
    b.small = ranks->all_gather_plain(b.small);
    b.receivers = ranks->all_gather_plain(b.receivers);
    std::uint64_t first = 0;
    for (SmallWater<D>& c : b.small) {
      c.first = first;
      first += c.count;
    }
  }
  replay_absorption(b);
  if (!b.state.empty())
    for (std::size_t i = 0; i < ps.size(); ++i) {
      const auto it = std::lower_bound(b.state.begin(), b.state.end(), place(ranks, i),
                                       [](const Receiver<D>& r, std::uint64_t a) { return r.at < a; });
      if (it == b.state.end() || it->at != place(ranks, i)) continue;
      ps.absorbed[i] = it->absorbed;
      ps.m[i] = it->m;
      ps.v[i] = it->v;
    }
  std::size_t count = 0;
  for (std::size_t k = 0; k < local; ++k) {
    const std::size_t i = b.mine[k];
    const auto c = std::find_if(b.small.begin(), b.small.end(), [&](const SmallWater<D>& s) { return s.at == place(ranks, i); });
    if (!b.absorbed[static_cast<std::size_t>(c - b.small.begin())]) continue;
    ps.m[i] = 0.0;
    ps.queue_remove(i);
    ++count;
  }
  return count;
}

/// A full emission store whose target is free of the particles of its neighbourhood (emit_new):
/// its place in the one-process storage, its target and the spacing of its particle.
template <int D>
struct EmissionCandidate {
  std::uint64_t at;
  Vec<D> target;
  double spacing;
};

/// Which `candidates` create a particle: one after the other in the one-process order (by place),
/// each whose target lies at least kPlacementGap spacings from the targets placed before it.
/// Decomposed, every rank's candidates are gathered and every rank places them all.
template <int D>
std::vector<std::uint64_t> place_emissions(std::vector<EmissionCandidate<D>> candidates, const Decomposition<D>* ranks) {
  if (ranks) candidates = ranks->all_gather_plain(candidates);
  std::sort(candidates.begin(), candidates.end(), [](const auto& a, const auto& b) { return a.at < b.at; });
  std::vector<std::uint64_t> granted;
  typename ParticleSet<D>::VecArray placed;
  for (const EmissionCandidate<D>& c : candidates) {
    bool free = true;
    for (const Vec<D>& x : placed) free = free && (x - c.target).norm() >= kPlacementGap * c.spacing;
    if (!free) continue;
    placed.push_back(c.target);
    granted.push_back(c.at);
  }
  return granted;
}

/// Creates water particles from full emission stores at targets free of any particle (a store
/// whose target still holds departing water waits); returns stores of particles that are no
/// longer exposed to m_p (as far as they have room). A new particle takes at most one full water
/// particle's mass; the rest of the store waits for the next free target, so a store that waited
/// long does not leave as one heavy particle that sinks through the water (test
/// porous/a_large_emission_store_leaves_in_particles_of_at_most_a_full_mass). Targets are placed
/// in storage order (place_emissions); the creations are queued in it, each particle's in
/// w.emitters.
template <int D>
std::size_t emit_new(ParticleSet<D>& ps, const PorousParams& p, PorousWork<D>& w, const Decomposition<D>* ranks) {
  std::vector<EmissionCandidate<D>> candidates;
  std::vector<std::size_t> mine;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (!own(ranks, i) || !w.porous[i] || ps.emit_store[i] <= 0.0) continue;
    if (!w.exposed[i]) {
      const double back = std::min(ps.emit_store[i], std::max(0.0, w.slot[i].capacity - ps.absorbed[i]));
      ps.absorbed[i] += back;
      ps.emit_store[i] -= back;
      continue;
    }
    if (!w.placeable[i] || ps.emit_store[i] < p.create_fraction * p.water_mass) continue;
    candidates.push_back({place(ranks, i), w.target[i], w.spacing[i]});
    mine.push_back(i);
  }
  const std::vector<std::uint64_t> granted = place_emissions(candidates, ranks);
  std::size_t count = 0;
  for (const std::size_t i : mine) {
    if (!std::binary_search(granted.begin(), granted.end(), place(ranks, i))) continue;
    ParticleSet<D>& add = ps.additions();
    const std::size_t k = add.append();
    add.x[k] = w.target[i];
    add.v[k] = ps.v[i];
    add.m[k] = std::min(ps.emit_store[i], p.water_mass);
    add.h[k] = p.water_support;
    add.rho0[k] = partial_water_rest_density(p.fluid_density, p.water_mass, add.m[k],
                                             kernel::density_kernel<D>(p.density_kernel, 0.0, p.water_support));
    add.rho[k] = add.rho0[k];
    ps.emit_store[i] -= add.m[k];
    if (carries_held_water(ps, i)) ps.m[i] -= add.m[k];  // the new particle takes its share of i's momentum
    w.emitters.push_back(i);
    ++count;
  }
  return count;
}

}  // namespace

template <int D>
PorousStepCounts porous_step(ParticleSet<D>& ps, const NeighbourGrid<D>& nb, const PorousParams& params,
                             const Vec<D>& gravity, double dt, PorousWork<D>& w, const Decomposition<D>* ranks) {
  const std::size_t n = ps.size();
  w.slot.resize(n);
  for (auto* v : {&w.part, &w.porous, &w.exposed, &w.placeable, &w.seepage, &w.contact, &w.flowing}) v->resize(n);
  for (auto* v : {&w.pc, &w.pp, &w.ghost, &w.in, &w.a, &w.b, &w.relaxed, &w.spacing, &w.passed, &w.suction, &w.taken,
                  &w.rest_volume})
    v->resize(n);
  w.brought.resize(n);
  w.target.resize(n);
  w.emitters.clear();
  const bool fixed_contact = prepare_participants(ps, nb, params, gravity, dt, w);
  refresh(ranks, w.part, w.contact, w.slot, w.pc, w.pp);
  // Decomposed, every rank takes part in the scene-wide water columns (it may have no contact).
  if (fixed_contact || ranks) set_contact_pressure(ps, nb, params, gravity, w, ranks);
  pore_velocities(ps, nb, params, gravity, w);
  refresh(ranks, ps.pore_velocity, w.slot);
  PorousStepCounts counts;
  if (params.diffusion == PorousDiffusion::LenaertsLiteral) {
    diffuse_literal(ps, nb, dt, w);
    refresh(ranks, ps.absorbed, ps.m);
  } else {
    exposure(ps, nb, params, gravity, w);
    diffuse_conserving(ps, nb, params, dt, w, ranks);
    update_rigid_pore_pressure(ps, nb, params, gravity, w, ranks);
    counts.created = emit_new(ps, params, w, ranks);
    refresh(ranks, ps.absorbed, ps.emit_store, ps.m);  // absorb_small's receivers, after the stores' returns and emissions
  }
  counts.absorbed = absorb_small(ps, nb, params, w, ranks);
  update_rest_densities(ps, params, w);
  return counts;
}

template <int D>
double total_water(const ParticleSet<D>& ps) {
  double sum = 0.0;
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (ps.phase_of(i) == Phase::Water)
      sum += ps.m[i];
    else if (ps.has_porous_fields())
      sum += ps.absorbed[i] + ps.emit_store[i];
  return sum;
}

template PorousStepCounts porous_step<2>(ParticleSet<2>&, const NeighbourGrid<2>&, const PorousParams&, const Vec<2>&, double,
                                         PorousWork<2>&, const Decomposition<2>*);
template PorousStepCounts porous_step<3>(ParticleSet<3>&, const NeighbourGrid<3>&, const PorousParams&, const Vec<3>&, double,
                                         PorousWork<3>&, const Decomposition<3>*);
template double total_water<2>(const ParticleSet<2>&);
template double total_water<3>(const ParticleSet<3>&);

}  // namespace sc
