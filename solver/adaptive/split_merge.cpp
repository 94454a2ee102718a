#include "adaptive/split_merge.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

namespace sc {

namespace {

using R = FieldRule;
// One line per ParticleSet field (visit_fields names). A field missing here cannot be split or
// merged: field_rule throws.
constexpr std::array<std::pair<std::string_view, FieldRule>, 23> kRules{{
    {"position", R::Position},        {"velocity", R::Intensive},
    {"force", R::Extensive},          {"mass", R::Extensive},
    {"support_radius", R::Size},      {"density", R::Intensive},
    {"rest_density", R::Intensive},   {"pressure", R::Intensive},
    {"phase", R::Copy},               {"rough", R::Copy},
    {"id", R::Identity},              {"rigid", R::Copy},
    {"cluster", R::Copy},             {"strain_rate", R::Intensive},
    {"absorbed_water", R::Extensive}, {"emit_store", R::Extensive},
    {"saturation", R::Intensive},     {"porosity", R::Intensive},
    {"capillary_potential", R::Intensive}, {"pore_pressure", R::Intensive},
    {"pore_velocity", R::Intensive},  {"density_offset", R::Intensive},
    {"level", R::Level},
}};

[[noreturn]] void bad_rule(std::string_view name) {
  throw std::logic_error("adaptive: rule " + std::to_string(static_cast<int>(field_rule(name))) +
                         " does not apply to the type of field '" + std::string(name) + "'");
}

// Calls f(name, to_field, from_field) for every field, matched by name and type; `to` first gets
// the porous fields if `from` has them.
template <int D, class F>
void for_each_field_pair(const ParticleSet<D>& from, ParticleSet<D>& to, F&& f) {
  if (from.has_porous_fields()) to.add_porous_fields();
  to.visit_fields([&](std::string_view name, auto& dst) {
    from.visit_fields([&](std::string_view other, auto& src) {
      if constexpr (std::is_same_v<std::decay_t<decltype(dst)>, std::decay_t<decltype(src)>>)
        if (name == other) f(name, dst, std::as_const(src));
    });
  });
}

template <int D, class T>
void split_value(std::string_view name, const T& parent, T& c1, T& c2, const Vec<D>& offset) {
  const FieldRule rule = field_rule(name);
  if (rule == R::Identity) return;
  if (rule == R::Copy || rule == R::Intensive) { c1 = c2 = parent; return; }
  if constexpr (std::is_integral_v<T>) {
    if (rule != R::Level) bad_rule(name);
    c1 = c2 = static_cast<T>(parent - 1);
  } else if (rule == R::Extensive) {
    c1 = c2 = 0.5 * parent;
  } else if constexpr (std::is_same_v<T, Vec<D>>) {
    if (rule != R::Position) bad_rule(name);
    c1 = parent + offset;
    c2 = parent - offset;
  } else {
    if (rule != R::Size) bad_rule(name);
    c1 = c2 = parent * std::pow(0.5, 1.0 / D);
  }
}

template <int D, class T>
void merge_value(std::string_view name, const T& a, const T& b, double ma, double mb, T& out) {
  const FieldRule rule = field_rule(name);
  if (rule == R::Identity) return;
  if (rule == R::Copy) { out = a; return; }
  if constexpr (std::is_integral_v<T>) {
    if (rule != R::Level) bad_rule(name);
    out = static_cast<T>(a + 1);  // merge_pair checked a == b
  } else if (rule == R::Extensive) {
    out = a + b;
  } else if (rule == R::Intensive || rule == R::Position) {
    out = (ma * a + mb * b) / (ma + mb);
  } else if constexpr (std::is_same_v<T, double>) {
    out = std::pow(std::pow(a, D) + std::pow(b, D), 1.0 / D);  // Size: volumes add
  } else {
    bad_rule(name);
  }
}

template <int D>
std::vector<Vec<D>, Eigen::aligned_allocator<Vec<D>>> candidate_axes() {
  std::vector<Vec<D>, Eigen::aligned_allocator<Vec<D>>> axes;
  if constexpr (D == 2) {
    for (int k = 0; k < 8; ++k) axes.emplace_back(std::cos(k * pi / 8), std::sin(k * pi / 8));
  } else {
    const int lattice[13][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {1, -1, 0},
                                {1, 0, 1}, {1, 0, -1}, {0, 1, 1}, {0, 1, -1}, {1, 1, 1},
                                {1, 1, -1}, {1, -1, 1}, {1, -1, -1}};
    for (const auto& l : lattice) axes.push_back(Vec<3>(l[0], l[1], l[2]).normalized());
  }
  return axes;
}

}  // namespace

FieldRule field_rule(std::string_view field_name) {
  for (const auto& [name, rule] : kRules)
    if (name == field_name) return rule;
  throw std::logic_error("adaptive: ParticleSet field '" + std::string(field_name) +
                         "' has no split/merge rule (solver/adaptive/split_merge.cpp)");
}

template <int D>
void check_params(const AdaptiveParams& p) {
  const double bound = std::pow(2.0, 1.0 / D) * p.alpha;
  if (!(p.alpha > 0.0) || !(p.beta >= bound))
    throw std::invalid_argument("adaptive: need alpha > 0 and beta >= 2^(1/D) alpha = " +
                                std::to_string(bound) + " (hysteresis)");
  if (p.min_level > p.max_level || !(p.finest_volume > 0.0) || !(p.split_offset > 0.0) ||
      !(p.merge_distance > 0.0))
    throw std::invalid_argument("adaptive: need min_level <= max_level and positive "
                                "finest_volume, split_offset, merge_distance");
}

template <int D>
double size_of_level(int level, const AdaptiveParams& params) {
  return particle_size<D>(std::ldexp(params.finest_volume, level));
}

template <int D>
Decision decide(double elfs, int level, const AdaptiveParams& params) {
  const double r = size_of_level<D>(level, params);
  if (elfs < params.alpha * r && level > params.min_level) return Decision::Split;
  if (elfs > params.beta * r && level < params.max_level) return Decision::Merge;
  return Decision::Keep;
}

template <int D>
Vec<D> split_direction(const Vec<D>& x, double delta, std::span<const Vec<D>> others) {
  const auto axes = candidate_axes<D>();
  Vec<D> best = axes.front();
  double best_score = -1.0;
  for (const Vec<D>& e : axes) {
    double score = std::numeric_limits<double>::infinity();
    for (const Vec<D>& o : others)
      score = std::min({score, (x + delta * e - o).norm(), (x - delta * e - o).norm()});
    if (score > best_score) { best_score = score; best = e; }
  }
  return best;
}

template <int D>
std::size_t split_particle(const ParticleSet<D>& from, std::size_t i, const Vec<D>& e,
                           double delta, ParticleSet<D>& to) {
  if (from.level[i] == 0) throw std::invalid_argument("adaptive: a particle of level 0 cannot be split");
  const std::size_t a = to.append();
  const std::size_t b = to.append();
  const Vec<D> offset = delta * e;
  for_each_field_pair<D>(from, to, [&](std::string_view name, auto& dst, const auto& src) {
    split_value<D>(name, src[i], dst[a], dst[b], offset);
  });
  return a;
}

template <int D>
double merge_pair(const ParticleSet<D>& from, std::size_t i, std::size_t j, ParticleSet<D>& to) {
  if (from.phase[i] != from.phase[j])
    throw std::invalid_argument("adaptive: cannot merge particles of different phases");
  if (from.level[i] != from.level[j])
    throw std::invalid_argument("adaptive: cannot merge particles of different levels");
  const double mi = from.m[i], mj = from.m[j];
  const std::size_t k = to.append();
  for_each_field_pair<D>(from, to, [&](std::string_view name, auto& dst, const auto& src) {
    merge_value<D>(name, src[i], src[j], mi, mj, dst[k]);
  });
  const double reduced = mi * mj / (mi + mj);
  return 0.5 * reduced * (from.v[i] - from.v[j]).squaredNorm();
}

#define SC_ADAPTIVE_INSTANTIATE(D)                                                              \
  template void check_params<D>(const AdaptiveParams&);                                         \
  template double size_of_level<D>(int, const AdaptiveParams&);                                 \
  template Decision decide<D>(double, int, const AdaptiveParams&);                              \
  template Vec<D> split_direction<D>(const Vec<D>&, double, std::span<const Vec<D>>);          \
  template std::size_t split_particle<D>(const ParticleSet<D>&, std::size_t, const Vec<D>&,     \
                                         double, ParticleSet<D>&);                              \
  template double merge_pair<D>(const ParticleSet<D>&, std::size_t, std::size_t, ParticleSet<D>&);
SC_ADAPTIVE_INSTANTIATE(2)
SC_ADAPTIVE_INSTANTIATE(3)
#undef SC_ADAPTIVE_INSTANTIATE

}  // namespace sc
