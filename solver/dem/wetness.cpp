#include "dem/wetness.hpp"

#include <stdexcept>
#include <vector>

namespace sc::dem {

namespace {

/// Grains touching (wet radii overlap or meet), the neighbourhood the water spreads over.
template <int D>
bool touching(const Grains<D>& g, std::size_t i, std::size_t j, const Params& p) {
  return i != j && (g.x[j] - g.x[i]).norm() <= g.wet_radius(i, p) + g.wet_radius(j, p);
}

}  // namespace

template <int D>
void propagate_wetness(Grains<D>& g, const CellGrid<D>& grid, const Params& p, double dt) {
  if (p.propagation_rate * dt > 1.0) throw std::invalid_argument("propagate_wetness: k_p dt must be <= 1");
  const auto n = static_cast<std::ptrdiff_t>(g.size());
  std::vector<std::uint8_t> over(g.size());
  for (std::size_t i = 0; i < g.size(); ++i) over[i] = g.saturation(i, p) > p.wet_threshold;
  // Share each over-wet grain gives to each drier touching neighbour (start-of-step state).
  std::vector<double> share(g.size(), 0.0);
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t s = 0; s < n; ++s) {
    const auto i = static_cast<std::size_t>(s);
    if (!over[i]) continue;
    int receivers = 0;
    grid.for_each_near(g.x[i], [&](std::uint32_t j) { receivers += !over[j] && touching(g, i, j, p); });
    if (receivers > 0)
      share[i] = p.propagation_rate * dt * (g.water[i] - p.wet_threshold * g.capacity(i, p)) / receivers;
  }
  // Each grain sums what it gives and receives; the water moved carries its source's velocity, so
  // momentum is conserved too (the mass a grain moves includes the water it holds).
  std::vector<double> change(g.size(), 0.0);
  typename Grains<D>::VecArray momentum(g.size());
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t s = 0; s < n; ++s) {
    const auto i = static_cast<std::size_t>(s);
    double dw = 0.0;
    Vec<D> dp = Vec<D>::Zero();
    grid.for_each_near(g.x[i], [&](std::uint32_t j) {
      if (over[i] == over[j] || !touching(g, i, j, p)) return;
      const std::size_t from = over[i] ? i : j;
      const double w = over[i] ? -share[i] : share[j];
      dw += w;
      dp += w * g.v[from];
    });
    change[i] = dw;
    momentum[i] = g.mass(i) * g.v[i] + dp;
  }
  for (std::size_t i = 0; i < g.size(); ++i) {
    if (change[i] == 0.0) continue;
    g.water[i] += change[i];
    g.v[i] = momentum[i] / g.mass(i);
  }
}

template void propagate_wetness<2>(Grains<2>&, const CellGrid<2>&, const Params&, double);
template void propagate_wetness<3>(Grains<3>&, const CellGrid<3>&, const Params&, double);

}  // namespace sc::dem
