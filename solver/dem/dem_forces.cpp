#include "dem/dem_forces.hpp"

#include <algorithm>

namespace sc::dem {

namespace {

/// Volume of the bridge between i and j for Willett's law: a share of the water both hold.
template <int D>
double bridge_volume(const Grains<D>& g, std::size_t i, std::size_t j, const Params& p) {
  return p.bridge_liquid_fraction * (g.water[i] + g.water[j]) / p.water_density;
}

/// The bridge force on i (zero unless both grains hold water and the pair is not over-wet). Willett's
/// R of two unequal spheres is their harmonic mean radius 2 a_i a_j/(a_i + a_j) = 2 r_eff.
template <int D>
Vec<D> bridge_force(const Grains<D>& g, std::size_t i, std::size_t j, const Params& p, const Vec<D>& n, double gap,
                    double r_eff) {
  const double wi = g.saturation(i, p), wj = g.saturation(j, p);
  if (p.bridge == BridgeLaw::Paper) {
    if (gap > p.bridge_range) return Vec<D>::Zero();
    return paper_bridge_force<D>(p.bridge_coefficient, p.wet_threshold, wi, wj, g.v[j] - g.v[i], g.x[j] - g.x[i]);
  }
  if (p.bridge == BridgeLaw::Willett && wi > 0.0 && wj > 0.0 && 0.5 * (wi + wj) <= p.wet_threshold)
    return willett_force(2.0 * r_eff, gap, bridge_volume(g, i, j, p), p.surface_tension, p.contact_angle) * n;
  return Vec<D>::Zero();
}

/// Whether grains i and j can exert a force on each other: always with bridges, otherwise only when
/// their dry radii overlap (the wet radii are never larger).
template <int D>
bool may_interact(const Grains<D>& g, std::size_t i, std::size_t j, const Params& p) {
  const double reach = g.radius[i] + g.radius[j];
  return p.bridge != BridgeLaw::None || (g.x[j] - g.x[i]).squaredNorm() < reach * reach;
}

/// Whether grain i can touch the wall: its dry radius reaches the plane (the wet radius is never
/// larger). Most grains of a box are far from its walls, and this test spares them the contact law.
template <int D>
bool may_touch(const Grains<D>& g, std::size_t i, const Plane<D>& wall) {
  return (g.x[i] - wall.point).dot(wall.normal) < g.radius[i];
}

/// The spring grain i kept of its contact with `key` last step, or a relaxed one for a new contact.
/// The contacts are visited in the order they were kept (list order, or wall order), so the search
/// starts at `next`, just after the last one found, and wraps around: one comparison per contact
/// instead of a scan of all of them.
template <int D>
Spring<D> previous_spring(std::span<const Spring<D>> springs, std::uint32_t key, std::size_t& next) {
  const std::size_t n = springs.size();
  for (std::size_t k = 0, at = next; k < n; ++k, ++at) {
    if (at >= n) at -= n;  // next <= n, so at < 2n: one subtraction wraps it, no division
    if (springs[at].other == key) {
      next = at + 1;
      return springs[at];
    }
  }
  Spring<D> fresh;
  fresh.other = key;
  return fresh;
}

/// The contacts of the grains that kept more than the contact history's capacity this step.
template <int D>
using Overflow = std::vector<std::pair<std::size_t, std::vector<Spring<D>>>>;

/// Keeps the overflowing grains' contacts, after growing the history. Each grain's contacts go to
/// its own slots, so the order of the list does not matter.
template <int D>
void keep_overflow(ContactHistory<D>& history, const Overflow<D>& overflow) {
  std::size_t needed = 0;
  for (const auto& [i, kept] : overflow) needed = std::max(needed, kept.size());
  history.grow(needed);
  for (const auto& [i, kept] : overflow) history.keep(i, kept);
}

/// Calls contacts_of(i, kept) for every grain i, which computes i's share of the step and lists in
/// `kept` the contacts it keeps in `history`, and keeps them there (growing the history when some
/// grain keeps more than its capacity). Dynamic schedule: a settling pile's lower grains have many
/// contacts and its upper ones few, so equal shares of the grain order are unequal work. Each grain's
/// results are its own: any schedule gives the same bits.
template <int D, class F>
void for_each_grain_keeping(std::size_t grains, ContactHistory<D>& history, F&& contacts_of) {
  const auto n = static_cast<std::ptrdiff_t>(grains);
  Overflow<D> overflow;
#pragma omp parallel
  {
    std::vector<Spring<D>> kept;
    Overflow<D> my_overflow;
#pragma omp for schedule(dynamic, 256)
    for (std::ptrdiff_t s = 0; s < n; ++s) {
      const auto i = static_cast<std::size_t>(s);
      kept.clear();
      contacts_of(i, kept);
      if (!history.keep(i, kept)) my_overflow.emplace_back(i, kept);
    }
#pragma omp critical(dem_contact_overflow)
    overflow.insert(overflow.end(), my_overflow.begin(), my_overflow.end());
  }
  keep_overflow(history, overflow);
}

/// The pair pass: every listed pair {i, j}, i < j, that may interact is evaluated once, from i's side
/// with the springs i keeps of it (Grains::springs), into the pair's slot of `contacts`.
template <int D>
void evaluate_pairs(Grains<D>& g, Contacts<D>& contacts, const Params& p, double dt) {
  contacts.pair.resize(contacts.near.pairs());
  contacts.acts.resize(contacts.near.pairs());
  for_each_grain_keeping(g.size(), g.springs, [&](std::size_t i, std::vector<Spring<D>>& kept) {
    std::size_t next = 0;
    contacts.near.for_each_owned(i, [&](std::uint32_t j, std::uint32_t q) {
      contacts.acts[q] = may_interact(g, i, j, p);
      if (!contacts.acts[q]) return;
      Spring<D> spring = previous_spring(g.springs.of(i), j, next);
      contacts.pair[q] = pair_force(g, i, j, p, dt, spring);
      if (contacts.pair[q].touching) kept.push_back(spring);
    });
  });
}

/// The gather: each grain sums its weight, its pairs' contacts in the order of its list (as evaluated
/// for the lower grain: from the higher one, the force negated and the other torque), then its
/// contacts with the walls if it may reach one (Contacts::near_wall), whose springs it keeps
/// (Grains::wall_springs). The terms and their order are those of each grain evaluating all its
/// contacts itself, and so are the sums' bits (a term differs at most in the sign of a zero, which
/// leaves a sum started at +0 or at a weight unchanged).
template <int D>
void gather_forces(Grains<D>& g, const Contacts<D>& contacts, const Params& p, const Vec<D>& gravity,
                   std::span<const Plane<D>> walls, double dt) {
  for_each_grain_keeping(g.size(), g.wall_springs, [&](std::size_t i, std::vector<Spring<D>>& kept) {
    Vec<D> f = g.mass(i) * gravity;
    Spin<D> t = Spin<D>::Zero();
    contacts.near.for_each_pair(i, [&](std::uint32_t q, bool lower) {
      if (!contacts.acts[q]) return;
      const ContactForce<D>& c = contacts.pair[q];
      if (lower) {
        f += c.force;
        t += c.torque;
      } else {
        f -= c.force;
        t += c.torque_other;
      }
    });
    std::size_t next = 0;
    for (std::size_t w = 0; contacts.near_wall[i] && w < walls.size(); ++w) {
      if (!may_touch(g, i, walls[w])) continue;
      Spring<D> spring = previous_spring(g.wall_springs.of(i), wall_key(w), next);
      const ContactForce<D> c = wall_force(g, i, walls[w], p, dt, spring);
      f += c.force;
      t += c.torque;
      if (c.touching) kept.push_back(spring);
    }
    g.force[i] = f;
    g.torque[i] = t;
  });
}

}  // namespace

template <int D>
double interaction_range(const Grains<D>& g, const Params& p) {
  double r = 0.0, w = 0.0;
  const auto n = static_cast<std::ptrdiff_t>(g.size());
#pragma omp parallel for schedule(static) reduction(max : r, w)  // exact: any threads
  for (std::ptrdiff_t i = 0; i < n; ++i) {
    r = std::max(r, g.radius[i]);
    w = std::max(w, g.water[i]);
  }
  double reach = 0.0;
  if (p.bridge == BridgeLaw::Paper) reach = p.bridge_range;
  if (p.bridge == BridgeLaw::Willett)
    reach = rupture_distance(p.bridge_liquid_fraction * 2.0 * w / p.water_density, p.contact_angle);
  return 2.0 * r + reach;
}

template <int D>
void bin_grains(const Grains<D>& g, const Params& p, CellGrid<D>& grid) {
  grid.build(std::span<const Vec<D>>(g.x.data(), g.x.size()), interaction_range(g, p));
}

template <int D>
void update_neighbours(const Grains<D>& g, const Params& p, std::span<const Plane<D>> walls, Contacts<D>& contacts) {
  const double range = interaction_range(g, p), skin = 0.1 * range;
  const std::span<const Vec<D>> x(g.x.data(), g.x.size());
  if (!contacts.near.stale(x, range)) return;
  contacts.near.build(x, range, skin);
  contacts.near_wall.resize(g.size());
  const auto n = static_cast<std::ptrdiff_t>(g.size());
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t s = 0; s < n; ++s) {
    const auto i = static_cast<std::size_t>(s);
    contacts.near_wall[i] = std::ranges::any_of(
        walls, [&](const Plane<D>& w) { return (g.x[i] - w.point).dot(w.normal) < g.radius[i] + skin; });
  }
}

template <int D>
ContactForce<D> pair_force(const Grains<D>& g, std::size_t i, std::size_t j, const Params& p, double dt,
                           Spring<D>& spring) {
  ContactForce<D> out{Vec<D>::Zero(), Spin<D>::Zero()};
  const Vec<D> d = g.x[j] - g.x[i];
  const double dist = d.norm();
  if (dist <= 0.0) return out;
  const Vec<D> n = d / dist;
  const double ai = g.wet_radius(i, p), aj = g.wet_radius(j, p);
  const double overlap = ai + aj - dist;
  const double r_eff = ai * aj / (ai + aj);
  if (p.bridge != BridgeLaw::None) out.force = bridge_force(g, i, j, p, n, -overlap, r_eff);
  if (overlap <= 0.0) return out;
  // Contact-point velocity of i relative to j; written (v_i − v_j) + (a_i ω_i + a_j ω_j) × n so that
  // j's evaluation is the exact negative.
  const Vec<D> vc = (g.v[i] - g.v[j]) + spin_cross<D>(ai * g.omega[i] + aj * g.omega[j], n);
  // 1 + (w_i + w_j), not (1 + w_i) + w_j: the same bits from either side of the pair.
  const Contact<D> c{n, overlap, vc, g.omega[i] - g.omega[j], 1.0 + (g.saturation(i, p) + g.saturation(j, p)),
                     p.friction, r_eff, ai, aj};
  const ContactForce<D> f = contact_force(c, p, dt, spring);
  out.force += f.force;
  out.torque = f.torque;
  out.torque_other = f.torque_other;
  out.touching = true;
  return out;
}

template <int D>
ContactForce<D> wall_force(const Grains<D>& g, std::size_t i, const Plane<D>& wall, const Params& p, double dt,
                           Spring<D>& spring) {
  const double ai = g.wet_radius(i, p);
  const double overlap = ai - (g.x[i] - wall.point).dot(wall.normal);
  if (overlap <= 0.0) return {Vec<D>::Zero(), Spin<D>::Zero()};
  const Vec<D> n = -wall.normal;
  const Vec<D> vc = g.v[i] + spin_cross<D>(ai * g.omega[i], n);
  const Contact<D> c{n, overlap, vc, g.omega[i], 1.0 + g.saturation(i, p), wall.rough ? p.wall_friction : 0.0, ai, ai,
                     0.0};
  return contact_force(c, p, dt, spring);
}

template <int D>
void grain_forces(Grains<D>& g, Contacts<D>& contacts, const Params& p, const Vec<D>& gravity,
                  std::span<const Plane<D>> walls, double dt) {
  evaluate_pairs(g, contacts, p, dt);
  gather_forces(g, contacts, p, gravity, walls, dt);
}

template <int D>
void integrate(Grains<D>& g, const Params& p, double dt) {
  const auto n = static_cast<std::ptrdiff_t>(g.size());
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t s = 0; s < n; ++s) {
    const auto i = static_cast<std::size_t>(s);
    g.v[i] += (dt / g.mass(i)) * g.force[i];
    if (p.rotation) g.omega[i] += (dt / g.inertia(i)) * g.torque[i];
    g.x[i] += dt * g.v[i];
  }
}

template <int D>
void step(Grains<D>& g, Contacts<D>& contacts, const Params& p, const Vec<D>& gravity,
          std::span<const Plane<D>> walls, double dt) {
  update_neighbours(g, p, walls, contacts);
  grain_forces(g, contacts, p, gravity, walls, dt);
  integrate(g, p, dt);
}

#define SC_DEM_FORCES(D)                                                                                       \
  template double interaction_range<D>(const Grains<D>&, const Params&);                                      \
  template void bin_grains<D>(const Grains<D>&, const Params&, CellGrid<D>&);                                \
  template ContactForce<D> pair_force<D>(const Grains<D>&, std::size_t, std::size_t, const Params&, double,  \
                                         Spring<D>&);                                                        \
  template ContactForce<D> wall_force<D>(const Grains<D>&, std::size_t, const Plane<D>&, const Params&, double, \
                                         Spring<D>&);                                                        \
  template void update_neighbours<D>(const Grains<D>&, const Params&, std::span<const Plane<D>>, Contacts<D>&); \
  template void grain_forces<D>(Grains<D>&, Contacts<D>&, const Params&, const Vec<D>&,                     \
                                std::span<const Plane<D>>, double);                                          \
  template void integrate<D>(Grains<D>&, const Params&, double);                                              \
  template void step<D>(Grains<D>&, Contacts<D>&, const Params&, const Vec<D>&, std::span<const Plane<D>>,       \
                        double);
SC_DEM_FORCES(2)
SC_DEM_FORCES(3)
#undef SC_DEM_FORCES

}  // namespace sc::dem
