// Adaptive sampling: split/merge identities, hysteresis, stable pairing, elfs of an analytic slab.
#include <boost/test/unit_test.hpp>
#include <algorithm>

#include <cmath>
#include <random>
#include <stdexcept>
#include <type_traits>

#include "adaptive/feature_size.hpp"
#include "adaptive/split_merge.hpp"

using namespace sc;
namespace tt = boost::test_tools;

BOOST_TEST_DONT_PRINT_LOG_VALUE(sc::Decision)

namespace {

// A sand particle with every floating-point field set to a distinct non-trivial value.
template <int D>
std::size_t add_particle(ParticleSet<D>& ps, double mass, const Vec<D>& x, const Vec<D>& v,
                         double absorbed, double saturation, std::uint8_t level = 1) {
  ps.add_porous_fields();
  const std::size_t i = ps.append();
  ps.level[i] = level;
  ps.x[i] = x; ps.v[i] = v; ps.m[i] = mass; ps.rho0[i] = 1000.0; ps.rho[i] = 1010.0 + mass;
  ps.h[i] = 2.0 * std::pow(mass / ps.rho0[i], 1.0 / D);
  ps.p[i] = 50.0 * mass; ps.phase[i] = static_cast<std::uint8_t>(Phase::Sand);
  ps.absorbed[i] = absorbed; ps.emit_store[i] = 0.1 * absorbed; ps.saturation[i] = saturation;
  ps.porosity[i] = 0.4; ps.capillary[i] = 3.0 * saturation; ps.pore_pressure[i] = 7.0 * mass;
  ps.strain_rate[i] = 0.25; ps.force[i] = v * mass; ps.pore_velocity[i] = 0.5 * v;
  return i;
}

template <int D>
Vec<D> momentum(const ParticleSet<D>& ps) {
  Vec<D> p = Vec<D>::Zero();
  for (std::size_t i = 0; i < ps.size(); ++i) p += ps.m[i] * ps.v[i];
  return p;
}

double total(const std::vector<double>& f) {
  double s = 0.0;
  for (double v : f) s += v;
  return s;
}

template <int D>
double kinetic(const ParticleSet<D>& ps) {
  double e = 0.0;
  for (std::size_t i = 0; i < ps.size(); ++i) e += 0.5 * ps.m[i] * ps.v[i].squaredNorm();
  return e;
}

template <int D>
Vec<D> centre_of_mass(const ParticleSet<D>& ps) {
  Vec<D> c = Vec<D>::Zero();
  for (std::size_t i = 0; i < ps.size(); ++i) c += ps.m[i] * ps.x[i];
  return c / total(ps.m);
}

template <class A, class B>
bool close(const A& a, const B& b, double rel = 1e-12) {
  return (a - b).norm() <= rel * std::max(1.0, b.norm());
}

// Every field of `a` particle i equals that of `b` particle j (relative 1e-12), except ids.
template <int D>
void check_same_particle(const ParticleSet<D>& a, std::size_t i, ParticleSet<D>& b, std::size_t j) {
  b.visit_fields([&](std::string_view name, auto& fb) {
    a.visit_fields([&](std::string_view other, auto& fa) {
      using T = typename std::decay_t<decltype(fa)>::value_type;
      if constexpr (std::is_same_v<std::decay_t<decltype(fa)>, std::decay_t<decltype(fb)>>) {
        if (name != other || name == "id") return;
        BOOST_TEST_CONTEXT("field " << name) {
          if constexpr (std::is_same_v<T, Vec<D>>)
            BOOST_TEST(close(fa[i], fb[j]));
          else if constexpr (std::is_floating_point_v<T>)
            BOOST_TEST(fa[i] == fb[j], tt::tolerance(1e-12));
          else
            BOOST_TEST(fa[i] == fb[j]);
        }
      }
    });
  });
}

/// Neighbours for adapt_pass and pair_merge_candidates: every particle of ps, whatever i.
template <int D>
auto every_particle(const ParticleSet<D>& ps) {
  return [&ps](std::size_t) {
    std::vector<std::size_t> j(ps.size());
    for (std::size_t k = 0; k < j.size(); ++k) j[k] = k;
    return j;
  };
}

template <int D>
AdaptiveParams params_for(double r0) {
  AdaptiveParams p;
  p.alpha = 2.0;
  p.beta = std::pow(2.0, 1.0 / D) * p.alpha;  // the hysteresis bound itself
  p.finest_volume = std::pow(r0, D);
  p.min_level = 0;
  p.max_level = 4;
  return p;
}

template <int D>
void split_then_merge_is_identity() {
  ParticleSet<D> parent, kids, back;
  Vec<D> x, v, e;
  for (int d = 0; d < D; ++d) { x[d] = 0.3 + 0.1 * d; v[d] = -1.0 + 0.7 * d; e[d] = 1.0 + d; }
  add_particle<D>(parent, 0.016, x, v, 0.003, 0.6);
  const std::size_t a = split_particle<D>(parent, 0, e.normalized(), 0.004, kids);
  BOOST_TEST_REQUIRE(kids.size() == 2u);
  BOOST_TEST(merge_pair<D>(kids, a, a + 1, back) == 0.0);  // equal child velocities: no loss
  check_same_particle<D>(parent, 0, back, 0);
}

// The slab |x_0 - 0.5| < T/2 = 0.2 on a grid whose nodes do not fall on its faces or centre.
template <int D>
void slab_elfs_is_half_thickness_plus_depth() {
  BackgroundGrid<D> grid;
  grid.origin = Vec<D>::Constant(-0.013);
  grid.dx = D == 2 ? 1.0 / 64 : 1.0 / 32;
  grid.n.fill(D == 2 ? 68 : 35);
  std::vector<double> f(grid.size());
  for (std::size_t k = 0; k < f.size(); ++k) f[k] = std::abs(grid.node(k)[0] - 0.5) - 0.2;
  const FeatureSize<D> fs = feature_size<D>(grid, f, FeatureSizeParams{});
  BOOST_TEST_REQUIRE(!fs.medial_axis.empty());
  for (const Vec<D>& q : fs.medial_axis) BOOST_TEST(q[0] == 0.5, tt::tolerance(1e-12));
  for (double l : fs.lfs) BOOST_TEST(l == 0.2, tt::tolerance(1e-12));
  double worst_distance = 0.0, worst_elfs = 0.0;
  for (std::size_t k = 0; k < f.size(); ++k) {
    worst_distance = std::max(worst_distance, std::abs(fs.distance[k] - f[k]));
    worst_elfs = std::max(worst_elfs, std::abs(fs.elfs[k] - (0.2 + std::abs(f[k]))));
  }
  // Exact up to rounding: the slab faces are resolved exactly by the edge crossings.
  BOOST_TEST(worst_distance <= 1e-12);
  BOOST_TEST(worst_elfs <= 1e-12);
  // Inside, elfs grows with depth: T/2 + 0.05 at depth 0.05, T at the centre (interpolated
  // off-node: the kink at the centre costs at most one cell).
  Vec<D> inside = Vec<D>::Constant(0.41), centre = Vec<D>::Constant(0.41);
  inside[0] = 0.35;
  centre[0] = 0.5;
  BOOST_TEST(sample_grid<D>(grid, fs.elfs, inside) == 0.25, tt::tolerance(1e-12));
  BOOST_TEST(sample_grid<D>(grid, fs.elfs, centre) == 0.4, tt::tolerance(grid.dx / 0.4));
}

}  // namespace

BOOST_AUTO_TEST_SUITE(adaptive)

// A disc of radius R = 0.3: its medial axis is the centre, so lfs = R on the whole circle and
// elfs = 2R at the centre. The circle is only resolved to O(dx^2) by the edge crossings; without
// the direction test of the medial axis lfs fell to 0.04 here.
BOOST_AUTO_TEST_CASE(elfs_of_a_disc) {
  BackgroundGrid<2> grid;
  grid.origin = Vec<2>::Constant(-0.013);
  grid.dx = 1.0 / 64;
  grid.n.fill(68);
  std::vector<double> f(grid.size());
  const Vec<2> c(0.5, 0.5);
  for (std::size_t k = 0; k < f.size(); ++k) f[k] = (grid.node(k) - c).norm() - 0.3;
  const FeatureSize<2> fs = feature_size<2>(grid, f, FeatureSizeParams{});
  double lo = 1.0, hi = 0.0;
  for (double l : fs.lfs) { lo = std::min(lo, l); hi = std::max(hi, l); }
  BOOST_TEST_MESSAGE("disc lfs in [" << lo << ", " << hi << "], elfs(centre) = "
                     << sample_grid<2>(grid, fs.elfs, c));
  BOOST_TEST(lo >= 0.3 - 0.5 * grid.dx);  // the lfs of a disc of radius 0.3 is 0.3, within half a cell
  BOOST_TEST(hi <= 0.3 + 0.5 * grid.dx);
  // The centre is a kink of elfs: off-node interpolation costs up to one cell.
  BOOST_TEST(sample_grid<2>(grid, fs.elfs, c) == 0.6, tt::tolerance(grid.dx / 0.6));
}

BOOST_AUTO_TEST_CASE(every_particle_field_has_a_split_merge_rule) {
  ParticleSet<3> ps;
  std::size_t fields = 0;
  ps.visit_fields([&](std::string_view name, auto&) {
    ++fields;
    BOOST_CHECK_NO_THROW(field_rule(name));
  });
  BOOST_TEST(fields > 10u);
  BOOST_CHECK_THROW(field_rule("not_a_field"), std::logic_error);
}

BOOST_AUTO_TEST_CASE(split_conserves_mass_momentum_centre_and_water) {
  ParticleSet<3> ps, kids;
  add_particle<3>(ps, 0.008, Vec<3>(0.1, 0.2, 0.3), Vec<3>(1.5, -2.0, 0.25), 0.002, 0.4, 3);
  const double delta = 0.5 * particle_size<3>(0.004 / 1000.0);
  split_particle<3>(ps, 0, Vec<3>(0, 0, 1), delta, kids);
  BOOST_TEST(total(kids.m) == 0.008, tt::tolerance(1e-12));
  BOOST_TEST(total(kids.absorbed) == 0.002, tt::tolerance(1e-12));
  BOOST_TEST(total(kids.emit_store) == 0.0002, tt::tolerance(1e-12));
  BOOST_TEST(close(momentum(kids), momentum(ps)));
  BOOST_TEST(close(centre_of_mass(kids), ps.x[0]));
  BOOST_TEST(kinetic(kids) == kinetic(ps), tt::tolerance(1e-12));
  BOOST_TEST((kids.x[0] - kids.x[1]).norm() == 2 * delta, tt::tolerance(1e-12));
  BOOST_TEST(kids.h[0] == ps.h[0] / std::cbrt(2.0), tt::tolerance(1e-12));
  BOOST_TEST(kids.saturation[1] == 0.4);
  BOOST_TEST(kids.id[0] != kids.id[1]);
  BOOST_TEST(kids.level[0] == 2);
  BOOST_TEST(kids.level[1] == 2);
}

BOOST_AUTO_TEST_CASE(merge_conserves_mass_momentum_centre_and_reports_energy_loss) {
  ParticleSet<3> ps, out;
  add_particle<3>(ps, 0.004, Vec<3>(0.1, 0.2, 0.3), Vec<3>(1.5, -2.0, 0.25), 0.001, 0.2);
  add_particle<3>(ps, 0.006, Vec<3>(0.11, 0.19, 0.305), Vec<3>(-0.5, 1.0, 3.0), 0.0025, 0.9);
  const double removed = merge_pair<3>(ps, 0, 1, out);
  BOOST_TEST_REQUIRE(out.size() == 1u);
  BOOST_TEST(out.m[0] == 0.01, tt::tolerance(1e-12));
  BOOST_TEST(out.absorbed[0] == 0.0035, tt::tolerance(1e-12));
  BOOST_TEST(close(momentum(out), momentum(ps)));
  BOOST_TEST(close(out.x[0], centre_of_mass(ps)));
  BOOST_TEST(out.saturation[0] == (0.004 * 0.2 + 0.006 * 0.9) / 0.01, tt::tolerance(1e-12));
  BOOST_TEST(out.h[0] == std::cbrt(std::pow(ps.h[0], 3) + std::pow(ps.h[1], 3)), tt::tolerance(1e-12));
  const double mu = 0.004 * 0.006 / 0.01;
  BOOST_TEST(removed == 0.5 * mu * (ps.v[0] - ps.v[1]).squaredNorm(), tt::tolerance(1e-12));
  BOOST_TEST(removed == kinetic(ps) - kinetic(out), tt::tolerance(1e-12));
  BOOST_TEST(removed == 0.024675, tt::tolerance(1e-12));  // 0.5 * 0.0024 * 20.5625
}

BOOST_AUTO_TEST_CASE(merge_refuses_different_phases) {
  ParticleSet<2> ps, out;
  add_particle<2>(ps, 0.1, Vec<2>(0, 0), Vec<2>(0, 0), 0.0, 0.0);
  add_particle<2>(ps, 0.1, Vec<2>(0.01, 0), Vec<2>(0, 0), 0.0, 0.0);
  ps.phase[1] = static_cast<std::uint8_t>(Phase::Water);
  BOOST_CHECK_THROW(merge_pair<2>(ps, 0, 1, out), std::invalid_argument);
}

BOOST_AUTO_TEST_CASE(merge_raises_the_level_split_lowers_it_and_level_0_does_not_split) {
  ParticleSet<2> ps, out;
  add_particle<2>(ps, 0.1, Vec<2>(0, 0), Vec<2>(0, 0), 0.0, 0.0, 0);
  add_particle<2>(ps, 0.1, Vec<2>(0.01, 0), Vec<2>(0, 0), 0.0, 0.0, 0);
  merge_pair<2>(ps, 0, 1, out);
  BOOST_TEST(out.level[0] == 1);
  split_particle<2>(out, 0, Vec<2>(1, 0), 0.001, out);
  BOOST_TEST(out.level[1] == 0);
  BOOST_TEST(out.level[2] == 0);
  BOOST_CHECK_THROW(split_particle<2>(ps, 0, Vec<2>(1, 0), 0.001, out), std::invalid_argument);
  ps.level[1] = 1;
  BOOST_CHECK_THROW(merge_pair<2>(ps, 0, 1, out), std::invalid_argument);  // levels differ
}

BOOST_AUTO_TEST_CASE(split_then_merge_returns_the_parent_2d) { split_then_merge_is_identity<2>(); }
BOOST_AUTO_TEST_CASE(split_then_merge_returns_the_parent_3d) { split_then_merge_is_identity<3>(); }

BOOST_AUTO_TEST_CASE(hysteresis_bound_is_enforced) {
  AdaptiveParams p = params_for<3>(0.01);
  BOOST_CHECK_NO_THROW(check_params<3>(p));
  p.beta = 1.25 * p.alpha;  // below 2^(1/3) = 1.2599
  BOOST_CHECK_THROW(check_params<3>(p), std::invalid_argument);
  AdaptiveParams q = params_for<2>(0.01);
  BOOST_CHECK_NO_THROW(check_params<2>(q));
  q.beta = 1.4 * q.alpha;  // below 2^(1/2) = 1.4142: the 2-D bound
  BOOST_CHECK_THROW(check_params<2>(q), std::invalid_argument);
  q.beta = 3.0;
  q.min_level = 5;
  BOOST_CHECK_THROW(check_params<2>(q), std::invalid_argument);
}

// Random elfs and levels: a split child never wants to merge and a merged particle never wants to
// split at the same elfs. With beta just below the bound the same sampling finds violations.
template <int D>
std::size_t count_flip_flops(const AdaptiveParams& p, std::size_t& splits, std::size_t& merges) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::uniform_int_distribution<int> level(p.min_level, p.max_level);
  std::size_t flips = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const int L = level(rng);
    const double elfs = 12.0 * particle_size<D>(std::ldexp(p.finest_volume, L)) * u(rng);
    const Decision d = decide<D>(elfs, L, p);
    splits += d == Decision::Split;
    merges += d == Decision::Merge;
    if (d == Decision::Split && decide<D>(elfs, L - 1, p) == Decision::Merge) ++flips;
    if (d == Decision::Merge && decide<D>(elfs, L + 1, p) == Decision::Split) ++flips;
  }
  return flips;
}

BOOST_AUTO_TEST_CASE(hysteresis_on_random_elfs) {
  std::size_t splits = 0, merges = 0;
  BOOST_TEST(count_flip_flops<3>(params_for<3>(0.01), splits, merges) == 0u);
  BOOST_TEST(count_flip_flops<2>(params_for<2>(0.01), splits, merges) == 0u);
  BOOST_TEST(splits > 1000u);
  BOOST_TEST(merges > 1000u);
  AdaptiveParams bad = params_for<3>(0.01);
  bad.beta = 0.9 * std::cbrt(2.0) * bad.alpha;
  BOOST_TEST(count_flip_flops<3>(bad, splits, merges) > 100u);
}

BOOST_AUTO_TEST_CASE(levels_bound_split_and_merge) {
  const AdaptiveParams p = params_for<3>(0.01);
  BOOST_TEST(size_of_level<3>(4, p) == 0.01 * std::cbrt(16.0), tt::tolerance(1e-14));  // the volume doubles per level
  BOOST_TEST(decide<3>(1e-9, 0, p) == Decision::Keep);
  BOOST_TEST(decide<3>(1e-9, 1, p) == Decision::Split);
  BOOST_TEST(decide<3>(1e9, 4, p) == Decision::Keep);
  BOOST_TEST(decide<3>(1e9, 3, p) == Decision::Merge);
}

BOOST_AUTO_TEST_CASE(split_direction_points_away_from_a_neighbour) {
  FeatureSize<2>::VecArray others{Vec<2>(0.01, 0.0)};
  const Vec<2> e = split_direction<2>(Vec<2>(0, 0), 0.005, std::span<const Vec<2>>(others));
  BOOST_TEST(std::abs(e[0]) < 1e-12);  // perpendicular to the neighbour direction
  BOOST_TEST(e.norm() == 1.0, tt::tolerance(1e-12));
  FeatureSize<3>::VecArray none;
  const Vec<3> e3 = split_direction<3>(Vec<3>::Zero(), 0.005, std::span<const Vec<3>>(none));
  BOOST_TEST(close(e3, Vec<3>(1, 0, 0)));  // nothing around: the first candidate
}

BOOST_AUTO_TEST_CASE(merge_pairing_is_nearest_same_level_in_index_order) {
  ParticleSet<2> ps;
  const double m = 0.1 * 0.1 * 1000.0;  // level 2 for r0 = 0.05
  for (double x : {0.0, 0.1, 0.35, 0.21, 0.5})
    add_particle<2>(ps, m, Vec<2>(x, 0), Vec<2>(0, 0), 0.0, 0.0, 2);
  ps.m[4] = 2 * m;  // another level: never paired with the others
  ps.level[4] = 3;
  AdaptiveParams p = params_for<2>(0.05);
  const auto all = every_particle(ps);
  const auto pairs = pair_merge_candidates<2>(ps, {0, 1, 2, 3, 4}, p, all);
  BOOST_TEST_REQUIRE(pairs.size() == 2u);
  BOOST_TEST((pairs[0] == std::pair<std::size_t, std::size_t>(0, 1)));
  BOOST_TEST((pairs[1] == std::pair<std::size_t, std::size_t>(2, 3)));
}

BOOST_AUTO_TEST_CASE(adapt_pass_conserves_totals_and_reports_energy) {
  ParticleSet<2> ps;
  const AdaptiveParams p = params_for<2>(0.01);
  const double m = 2 * 0.01 * 0.01 * 1000.0;  // level 1
  std::vector<double> elfs;
  for (int k = 0; k < 6; ++k) {
    add_particle<2>(ps, m, Vec<2>(0.014 * k, 0.0), Vec<2>(0.3 * k, -0.1 * k * k), 1e-4 * k, 0.1);
    elfs.push_back(k < 2 ? 1e-6 : 1.0);  // two splits, then two merges of neighbours
  }
  const Vec<2> p0 = momentum(ps), c0 = centre_of_mass(ps);
  const double m0 = total(ps.m), w0 = total(ps.absorbed), e0 = kinetic(ps);
  const auto all = every_particle(ps);
  const AdaptStats s = adapt_pass<2>(ps, elfs, p, all);
  BOOST_TEST(ps.compact());
  BOOST_TEST(s.splits == 2u);
  BOOST_TEST(s.merges == 2u);
  BOOST_TEST(ps.size() == 6u);
  BOOST_TEST(total(ps.m) == m0, tt::tolerance(1e-12));
  BOOST_TEST(total(ps.absorbed) == w0, tt::tolerance(1e-12));
  BOOST_TEST(close(momentum(ps), p0));
  BOOST_TEST(close(centre_of_mass(ps), c0));
  BOOST_TEST(s.energy_removed == e0 - kinetic(ps), tt::tolerance(1e-12));
}

// A pass over particles that all ask to merge (and one that asks to split), r0 = 0.01 m, so a
// level-1 particle merges within 1.5 r1 = 0.0212 m: water 0 pairs with its nearest partner 2
// (0.010 m away), not with 1 (0.018 m); a level-0 and a level-1 water particle, water beside
// sand, and two wall particles side by side are left alone; the level-2 particle splits into two
// level-1 children split_offset r1 from its place on either side. Nothing else changes.
BOOST_AUTO_TEST_CASE(a_pass_merges_nearest_partners_of_one_level_and_phase_and_splits_by_the_childs_size) {
  ParticleSet<2> ps;
  const AdaptiveParams p = params_for<2>(0.01);
  const double m1 = 2 * 0.01 * 0.01 * 1000.0;  // level 1
  struct Seed { double x; std::uint8_t level; Phase phase; double elfs; };
  const std::vector<Seed> seeds{{0.0, 1, Phase::Water, 1.0},   {0.018, 1, Phase::Water, 1.0},
                                {0.010, 1, Phase::Water, 1.0}, {0.1, 0, Phase::Water, 1.0},
                                {0.105, 1, Phase::Water, 1.0}, {0.2, 1, Phase::Water, 1.0},
                                {0.205, 1, Phase::Sand, 1.0},  {0.3, 1, Phase::Boundary, 1.0},
                                {0.305, 1, Phase::Boundary, 1.0}, {0.4, 2, Phase::Water, 1e-6}};
  std::vector<double> elfs;
  for (const Seed& seed : seeds) {
    const double m = m1 * std::pow(2.0, seed.level - 1);
    const std::size_t i = add_particle<2>(ps, m, Vec<2>(seed.x, 0.0), Vec<2>::Zero(), 0.0, 0.0, seed.level);
    ps.phase[i] = static_cast<std::uint8_t>(seed.phase);
    elfs.push_back(seed.elfs);
  }
  const auto all = every_particle(ps);
  const AdaptStats s = adapt_pass<2>(ps, elfs, p, all);
  BOOST_TEST(ps.compact());
  BOOST_TEST(s.merges == 1u);
  BOOST_TEST(s.splits == 1u);
  BOOST_TEST_REQUIRE(ps.size() == 10u);
  std::vector<Vec<2>> children;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const double x = ps.x[i][0];
    BOOST_TEST_INFO("particle at " << ps.x[i].transpose() << ", level " << int(ps.level[i]));
    if (x > 0.39) {  // a child of the split
      BOOST_TEST(ps.level[i] == 1);
      children.push_back(ps.x[i]);
    } else if (x > 0.004 && x < 0.006) {  // the merged pair 0 and 2
      BOOST_TEST(ps.level[i] == 2);
      BOOST_TEST(ps.x[i][0] == 0.005, tt::tolerance(1e-12));
    } else {  // left alone: its seed's place and level
      const auto seed = std::find_if(seeds.begin(), seeds.end(), [&](const Seed& q) { return q.x == x; });
      BOOST_TEST_REQUIRE((seed != seeds.end() && seed != seeds.begin() && seed->x != 0.010));
      BOOST_TEST(ps.level[i] == seed->level);
      BOOST_TEST(ps.x[i][1] == 0.0);
    }
  }
  BOOST_TEST_REQUIRE(children.size() == 2u);
  const double r1 = std::sqrt(2.0) * 0.01;
  BOOST_TEST((children[0] - children[1]).norm() == 2.0 * p.split_offset * r1, tt::tolerance(1e-12));
  BOOST_TEST(close(0.5 * (children[0] + children[1]), Vec<2>(0.4, 0.0)));
}

BOOST_AUTO_TEST_CASE(elfs_of_a_slab_2d) { slab_elfs_is_half_thickness_plus_depth<2>(); }
BOOST_AUTO_TEST_CASE(elfs_of_a_slab_3d) { slab_elfs_is_half_thickness_plus_depth<3>(); }

BOOST_AUTO_TEST_SUITE_END()
