#include "adaptive/feature_size.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <queue>
#include <utility>

namespace sc {

template <int D>
std::size_t BackgroundGrid<D>::size() const {
  std::size_t s = 1;
  for (int d = 0; d < D; ++d) s *= static_cast<std::size_t>(n[d]);
  return s;
}

template <int D>
std::size_t BackgroundGrid<D>::index(const std::array<int, D>& c) const {
  std::size_t k = 0;
  for (int d = D - 1; d >= 0; --d) k = k * static_cast<std::size_t>(n[d]) + static_cast<std::size_t>(c[d]);
  return k;
}

template <int D>
std::array<int, D> BackgroundGrid<D>::coords(std::size_t k) const {
  std::array<int, D> c{};
  for (int d = 0; d < D; ++d) {
    c[d] = static_cast<int>(k % static_cast<std::size_t>(n[d]));
    k /= static_cast<std::size_t>(n[d]);
  }
  return c;
}

template <int D>
Vec<D> BackgroundGrid<D>::node(std::size_t k) const {
  const std::array<int, D> c = coords(k);
  Vec<D> x = origin;
  for (int d = 0; d < D; ++d) x[d] += c[d] * dx;
  return x;
}

namespace {

template <int D>
using Points = typename FeatureSize<D>::VecArray;

// Closest source of every node: value = offset[s] + |node - source s|, source = s (-1: none).
struct Propagation {
  std::vector<double> value;
  std::vector<std::int64_t> source;
};

template <int D>
std::vector<std::array<int, D>> neighbour_offsets() {
  std::vector<std::array<int, D>> out;
  int total = 1;
  for (int d = 0; d < D; ++d) total *= 3;
  for (int code = 0; code < total; ++code) {
    std::array<int, D> o{};
    int rest = code;
    for (int d = 0; d < D; ++d, rest /= 3) o[d] = rest % 3 - 1;
    if (std::any_of(o.begin(), o.end(), [](int v) { return v != 0; })) out.push_back(o);
  }
  return out;
}

template <int D>
bool in_grid(const BackgroundGrid<D>& grid, const std::array<int, D>& c) {
  for (int d = 0; d < D; ++d)
    if (c[d] < 0 || c[d] >= grid.n[d]) return false;
  return true;
}

// Lower corner of the grid cell holding y, clamped so that the cell lies inside the grid.
template <int D>
std::array<int, D> cell_of(const BackgroundGrid<D>& grid, const Vec<D>& y) {
  std::array<int, D> c{};
  for (int d = 0; d < D; ++d) {
    const int raw = static_cast<int>(std::floor((y[d] - grid.origin[d]) / grid.dx));
    c[d] = std::clamp(raw, 0, grid.n[d] - 2);
  }
  return c;
}

template <int D>
std::array<int, D> corner(std::array<int, D> base, int mask) {
  for (int d = 0; d < D; ++d) base[d] += (mask >> d) & 1;
  return base;
}

// Nodes whose value would exceed `reach` are not visited (value infinite, source -1), nor, when
// `f` is given, nodes outside the region (f >= 0) further than `outside_reach` from their source.
template <int D>
Propagation propagate(const BackgroundGrid<D>& grid, const Points<D>& sources,
                      const std::vector<double>& offsets, double reach,
                      const std::vector<double>* f = nullptr,
                      double outside_reach = std::numeric_limits<double>::infinity()) {
  Propagation p{std::vector<double>(grid.size(), std::numeric_limits<double>::infinity()),
                std::vector<std::int64_t>(grid.size(), -1)};
  using Item = std::pair<double, std::size_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  auto relax = [&](const std::array<int, D>& c, std::size_t s) {
    Vec<D> x = grid.origin;
    for (int d = 0; d < D; ++d) x[d] += c[d] * grid.dx;
    const double distance = (x - sources[s]).norm();
    const double v = offsets[s] + distance;
    const std::size_t k = grid.index(c);
    if (!(v < p.value[k]) || v > reach) return;
    if (f && (*f)[k] >= 0.0 && distance > outside_reach) return;
    p.value[k] = v;
    p.source[k] = static_cast<std::int64_t>(s);
    queue.emplace(v, k);
  };
  for (std::size_t s = 0; s < sources.size(); ++s)
    for (int mask = 0; mask < (1 << D); ++mask) relax(corner<D>(cell_of<D>(grid, sources[s]), mask), s);
  const auto offsets_nb = neighbour_offsets<D>();
  while (!queue.empty()) {
    const auto [v, k] = queue.top();
    queue.pop();
    if (v > p.value[k]) continue;
    const std::array<int, D> c = grid.coords(k);
    for (const auto& o : offsets_nb) {
      std::array<int, D> nb = c;
      for (int d = 0; d < D; ++d) nb[d] += o[d];
      if (in_grid<D>(grid, nb)) relax(nb, static_cast<std::size_t>(p.source[k]));
    }
  }
  return p;
}

// Calls f(k, b, d) for every node k and its forward axis neighbour b along axis d.
template <int D, class F>
void for_each_axis_pair(const BackgroundGrid<D>& grid, F&& f) {
  for (std::size_t k = 0; k < grid.size(); ++k) {
    const std::array<int, D> c = grid.coords(k);
    for (int d = 0; d < D; ++d) {
      if (c[d] + 1 >= grid.n[d]) continue;
      std::array<int, D> b = c;
      ++b[d];
      f(k, grid.index(b), d);
    }
  }
}

template <int D>
Points<D> surface_samples(const BackgroundGrid<D>& grid, const std::vector<double>& f) {
  Points<D> out;
  for_each_axis_pair<D>(grid, [&](std::size_t k, std::size_t b, int d) {
    if ((f[k] < 0.0) == (f[b] < 0.0)) return;
    Vec<D> y = grid.node(k);
    y[d] += f[k] / (f[k] - f[b]) * grid.dx;
    out.push_back(y);
  });
  return out;
}

template <int D>
Points<D> medial_axis(const BackgroundGrid<D>& grid, const Points<D>& surface,
                      const Propagation& closest, const FeatureSizeParams& params) {
  const double cos_max = std::cos(params.medial_angle);
  Points<D> out;
  for_each_axis_pair<D>(grid, [&](std::size_t k, std::size_t b, int) {
    if (closest.source[k] < 0 || closest.source[b] < 0) return;
    const Vec<D>& ca = surface[static_cast<std::size_t>(closest.source[k])];
    const Vec<D>& cb = surface[static_cast<std::size_t>(closest.source[b])];
    const Vec<D> diff = cb - ca;
    if (diff.norm() <= params.medial_jump * grid.dx) return;
    const Vec<D> a = grid.node(k), ab = grid.node(b) - a;
    const Vec<D> to_a = ca - a, to_b = cb - grid.node(b);
    if (!(to_a.dot(to_b) < cos_max * to_a.norm() * to_b.norm())) return;
    const double denom = 2.0 * ab.dot(diff);
    if (denom == 0.0) return;
    // The point of segment ab equidistant from ca and cb (their bisector plane).
    const double t = (cb.squaredNorm() - ca.squaredNorm() - 2.0 * a.dot(diff)) / denom;
    if (t >= 0.0 && t <= 1.0) out.push_back(a + t * ab);
  });
  return out;
}

// Distance from each surface sample to the medial-axis point closest to its cell's corners.
template <int D>
std::vector<double> lfs_at_samples(const BackgroundGrid<D>& grid, const Points<D>& surface,
                                   const Points<D>& medial, const Propagation& closest) {
  std::vector<double> lfs(surface.size(), std::numeric_limits<double>::infinity());
  for (std::size_t s = 0; s < surface.size(); ++s)
    for (int mask = 0; mask < (1 << D); ++mask) {
      const auto q = closest.source[grid.index(corner<D>(cell_of<D>(grid, surface[s]), mask))];
      if (q >= 0) lfs[s] = std::min(lfs[s], (surface[s] - medial[static_cast<std::size_t>(q)]).norm());
    }
  return lfs;
}

}  // namespace

template <int D>
FeatureSize<D> feature_size(const BackgroundGrid<D>& grid, const std::vector<double>& f,
                            const FeatureSizeParams& params) {
  FeatureSize<D> out;
  out.surface = surface_samples<D>(grid, f);
  // Nothing beyond elfs_max from the surface can change a clamped elfs: the elfs propagation stops
  // there. The medial axis matters only through min(lfs, lfs_max), and a medial point at depth d
  // is at least d from every surface sample, so the first two propagations stop at lfs_max + 2
  // cells (the axis-neighbour nodes around a medial point, and the cell corners of a sample, are
  // within a cell diagonal of it).
  const double reach = params.elfs_max;
  const double medial_reach = std::min(reach, params.lfs_max + 2.0 * grid.dx);
  const Propagation closest =
      propagate<D>(grid, out.surface, std::vector<double>(out.surface.size(), 0.0), medial_reach);
  out.distance = closest.value;
  for (std::size_t k = 0; k < f.size(); ++k)
    if (f[k] < 0.0) out.distance[k] = -out.distance[k];
  out.medial_axis = medial_axis<D>(grid, out.surface, closest, params);
  const Propagation to_medial =
      propagate<D>(grid, out.medial_axis, std::vector<double>(out.medial_axis.size(), 0.0), medial_reach);
  out.lfs = lfs_at_samples<D>(grid, out.surface, out.medial_axis, to_medial);
  std::vector<double> seed = out.lfs;
  for (double& s : seed) s = std::min(s, params.lfs_max);
  out.elfs = propagate<D>(grid, out.surface, seed, reach, &f, params.outside_reach).value;
  for (double& e : out.elfs) e = std::min(std::max(e, params.elfs_min), params.elfs_max);
  return out;
}

template <int D>
double sample_grid(const BackgroundGrid<D>& grid, const std::vector<double>& values,
                   const Vec<D>& x) {
  const std::array<int, D> base = cell_of<D>(grid, x);
  std::array<double, D> t{};
  for (int d = 0; d < D; ++d)
    t[d] = std::clamp((x[d] - grid.origin[d]) / grid.dx - base[d], 0.0, 1.0);
  double sum = 0.0;
  for (int mask = 0; mask < (1 << D); ++mask) {
    double w = 1.0;
    for (int d = 0; d < D; ++d) w *= (mask >> d) & 1 ? t[d] : 1.0 - t[d];
    sum += w * values[grid.index(corner<D>(base, mask))];
  }
  return sum;
}

template struct BackgroundGrid<2>;
template struct BackgroundGrid<3>;
template FeatureSize<2> feature_size<2>(const BackgroundGrid<2>&, const std::vector<double>&,
                                        const FeatureSizeParams&);
template FeatureSize<3> feature_size<3>(const BackgroundGrid<3>&, const std::vector<double>&,
                                        const FeatureSizeParams&);
template double sample_grid<2>(const BackgroundGrid<2>&, const std::vector<double>&, const Vec<2>&);
template double sample_grid<3>(const BackgroundGrid<3>&, const std::vector<double>&, const Vec<3>&);

}  // namespace sc
