#include "adaptive/adaptivity.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "porous/porous_flow.hpp"

namespace sc {

AdaptivitySpec read_adaptivity(JsonObject o, int dim) {
  AdaptivitySpec s;
  AdaptiveParams& p = s.params;
  p.alpha = o.positive("alpha", 1.0);
  const double bound = std::pow(2.0, 1.0 / dim) * p.alpha;
  p.beta = o.positive("beta", std::max(2.0, bound));
  if (p.beta < bound)
    o.fail("beta", "must be at least 2^(1/D) alpha = " + std::to_string(bound) +
                       " (hysteresis: a split child must not merge again at once)");
  p.min_level = 0;
  p.max_level = static_cast<int>(o.integer("max_level", 0, 6, 2));
  p.split_offset = o.in_range("split_offset", 0.0, 1.0, true, 0.5);
  p.merge_distance = o.in_range("merge_distance", 0.0, 4.0, true, 1.5);
  s.interval = o.integer("interval", 1, 1000000, 10);
  s.grid_cell = o.in_range("grid_cell", 0.25, 4.0, false, 1.0);
  s.blend_time = o.positive("blend_time", 0.005);
  s.feature.medial_jump = o.positive("medial_jump", 2.0);
  s.feature.medial_angle = o.in_range("medial_angle_deg", 0.0, 180.0, true, 60.0) * pi / 180.0;
  if (o.has("surface_lfs_max")) s.feature.lfs_max = o.positive("surface_lfs_max");  // in spacings here
  const std::string phases = o.one_of("phases", {"water", "sand", "water_and_sand"}, "water");
  s.adapt_water = phases != "sand";
  s.adapt_sand = phases != "water";
  if (o.has("forced_cycle")) {
    JsonObject f = o.object("forced_cycle");
    ForcedCycle c;
    c.period = f.positive("period");
    c.until = f.positive("until");
    f.finish();
    s.forced = c;
  }
  o.finish();
  return s;
}

template <int D>
double decision_band(const AdaptiveParams& p, double r_min, double grid_cell) {
  const auto r_at = [&](int level) { return r_min * std::pow(2.0, static_cast<double>(level) / D); };
  double band = p.max_level > p.min_level ? p.alpha * r_at(p.max_level) : 0.0;  // largest split threshold
  if (p.max_level > p.min_level) band = std::max(band, p.beta * r_at(p.max_level - 1));  // largest merge threshold
  return band + 2.0 * grid_cell;
}

template <int D>
void derive_adaptivity(AdaptivitySpec& spec, double spacing, double finest_volume) {
  AdaptiveParams& p = spec.params;
  p.finest_volume = finest_volume;
  const double r_min = particle_size<D>(finest_volume);
  spec.grid_cell *= spacing;
  spec.feature.elfs_min = 0.5 * p.alpha * r_min;
  spec.feature.elfs_max = decision_band<D>(p, r_min, spec.grid_cell);
  spec.feature.outside_reach = 2.0 * spec.grid_cell;
  spec.feature.lfs_max *= spacing;
  check_params<D>(p);
}

namespace {

template <int D>
bool adapted(const ParticleSet<D>& ps, const AdaptivitySpec& spec, std::size_t i) {
  const Phase ph = ps.phase_of(i);
  return (ph == Phase::Water && spec.adapt_water) || (ph == Phase::Sand && spec.adapt_sand);
}

// Signed distance to the union of balls of radius r_i around the adapted particles, at the nodes
// of `grid` (capped at one cell outside, so the zero crossings are those of the union).
template <int D>
std::vector<double> union_of_balls(const ParticleSet<D>& ps, const AdaptivitySpec& spec,
                                   const BackgroundGrid<D>& grid) {
  std::vector<double> f(grid.size(), grid.dx);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (!adapted(ps, spec, i)) continue;
    const double r = size_of_level<D>(ps.level[i], spec.params);
    const double reach = r + grid.dx;
    std::array<int, D> lo{}, hi{};
    for (int d = 0; d < D; ++d) {
      lo[d] = std::max(0, static_cast<int>(std::floor((ps.x[i][d] - reach - grid.origin[d]) / grid.dx)));
      hi[d] = std::min(grid.n[d] - 1, static_cast<int>(std::ceil((ps.x[i][d] + reach - grid.origin[d]) / grid.dx)));
    }
    std::array<int, D> c = lo;
    while (true) {
      // Node positions from the coordinates (grid.node(k) would divide k back into them).
      Vec<D> node = grid.origin;
      for (int d = 0; d < D; ++d) node[d] += c[d] * grid.dx;
      const double q = (node - ps.x[i]).squaredNorm();
      if (q < reach * reach) {  // farther nodes would get more than the cap grid.dx
        const std::size_t k = grid.index(c);
        f[k] = std::min(f[k], std::sqrt(q) - r);
      }
      int d = 0;
      while (d < D && ++c[d] > hi[d]) c[d] = lo[d], ++d;
      if (d == D) break;
    }
  }
  return f;
}

// A grid covering the adapted particles with three cells of margin beyond their largest ball.
template <int D>
BackgroundGrid<D> grid_around(const ParticleSet<D>& ps, const AdaptivitySpec& spec) {
  Vec<D> lo = Vec<D>::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  double r_max = 0.0;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (!adapted(ps, spec, i)) continue;
    lo = lo.cwiseMin(ps.x[i]);
    hi = hi.cwiseMax(ps.x[i]);
    r_max = std::max(r_max, size_of_level<D>(ps.level[i], spec.params));
  }
  BackgroundGrid<D> grid;
  grid.dx = spec.grid_cell;
  const double margin = r_max + 3.0 * grid.dx;
  grid.origin = lo - Vec<D>::Constant(margin);
  for (int d = 0; d < D; ++d) grid.n[d] = static_cast<int>(std::ceil((hi[d] - lo[d] + 2.0 * margin) / grid.dx)) + 1;
  return grid;
}

struct Totals {
  double mass = 0.0, water = 0.0, speed_weight = 0.0, position_weight = 0.0;
  std::array<double, 3> momentum{}, moment{};
};

template <int D>
Totals totals(const ParticleSet<D>& ps) {
  Totals t;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (!ps.moves(i)) continue;
    t.mass += ps.m[i];
    t.speed_weight += ps.m[i] * ps.v[i].norm();
    t.position_weight += ps.m[i] * ps.x[i].norm();
    for (int d = 0; d < D; ++d) {
      t.momentum[d] += ps.m[i] * ps.v[i][d];
      t.moment[d] += ps.m[i] * ps.x[i][d];
    }
  }
  t.water = total_water(ps);
  return t;
}

double distance(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

void record(const Totals& before, const Totals& after, AdaptAccount& a) {
  a.max_mass_rel_error = std::max(a.max_mass_rel_error, std::abs(after.mass - before.mass) / before.mass);
  if (before.speed_weight > 0.0)
    a.max_momentum_error = std::max(a.max_momentum_error, distance(after.momentum, before.momentum) / before.speed_weight);
  a.max_moment_error = std::max(a.max_moment_error, distance(after.moment, before.moment) / before.position_weight);
  if (before.water > 0.0)
    a.max_water_rel_error = std::max(a.max_water_rel_error, std::abs(after.water - before.water) / before.water);
}

// The decision input of every particle at time t: elfs, or the forced cycle's +inf / 0.
template <int D>
std::vector<double> decision_elfs(const ParticleSet<D>& ps, const AdaptivitySpec& spec, double t) {
  if (!spec.forced) return particle_elfs<D>(ps, spec);
  const bool merge_half = t < spec.forced->until && std::fmod(t, spec.forced->period) < 0.5 * spec.forced->period;
  const double forced = merge_half ? std::numeric_limits<double>::infinity() : 0.0;
  std::vector<double> e(ps.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (adapted(ps, spec, i)) e[i] = forced;
  return e;
}

}  // namespace

template <int D>
std::vector<double> particle_elfs(const ParticleSet<D>& ps, const AdaptivitySpec& spec) {
  std::vector<double> out(ps.size(), std::numeric_limits<double>::quiet_NaN());
  bool any = false;
  for (std::size_t i = 0; i < ps.size() && !any; ++i) any = adapted(ps, spec, i);
  if (!any) return out;
  const BackgroundGrid<D> grid = grid_around<D>(ps, spec);
  const FeatureSize<D> fs = feature_size<D>(grid, union_of_balls<D>(ps, spec, grid), spec.feature);
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (adapted(ps, spec, i)) out[i] = sample_grid<D>(grid, fs.elfs, ps.x[i]);
  return out;
}

template <int D>
AdaptChanges adapt_particles(ParticleSet<D>& ps, const NeighbourGrid<D>& nb, const AdaptivitySpec& spec, double t,
                             AdaptAccount& account) {
  const Totals before = totals(ps);
  const std::vector<double> elfs = decision_elfs<D>(ps, spec, t);
  AdaptStats stats = adapt_pass<D>(ps, elfs, spec.params, [&](std::size_t i) { return nb.of(i); });
  AdaptChanges changes;
  changes.queued_by = std::move(stats.queued_by);
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (ps.queued_for_removal(i)) changes.removed.push_back(i);
  ps.compact();
  ++account.passes;
  account.splits += stats.splits;
  account.merges += stats.merges;
  account.energy_removed += stats.energy_removed;
  record(before, totals(ps), account);
  return changes;
}

#define SC_ADAPTIVITY_INSTANTIATE(D)                                                                     \
  template double decision_band<D>(const AdaptiveParams&, double, double);                               \
  template void derive_adaptivity<D>(AdaptivitySpec&, double, double);                                 \
  template std::vector<double> particle_elfs<D>(const ParticleSet<D>&, const AdaptivitySpec&);           \
  template AdaptChanges adapt_particles<D>(ParticleSet<D>&, const NeighbourGrid<D>&, const AdaptivitySpec&, \
                                           double, AdaptAccount&);
SC_ADAPTIVITY_INSTANTIATE(2)
SC_ADAPTIVITY_INSTANTIATE(3)
#undef SC_ADAPTIVITY_INSTANTIATE

}  // namespace sc
