#include "neighbours/neighbour_grid.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace sc {

namespace {

inline bool are_neighbours(double r2, double hi, double hj) {
  const double hmax = std::max(hi, hj);
  return r2 <= hmax * hmax;
}

}  // namespace

template <int D>
void NeighbourGrid<D>::rebuild(const ParticleSet<D>& ps) {
  const std::size_t n = ps.size();
  offset_.assign(n + 1, 0);
  index_.clear();
  if (n == 0) return;

  double hmax = 0.0;
  Vec<D> lo = ps.x[0], hi = ps.x[0];
  for (std::size_t i = 0; i < n; ++i) {
    hmax = std::max(hmax, ps.h[i]);
    lo = lo.cwiseMin(ps.x[i]);
    hi = hi.cwiseMax(ps.x[i]);
  }
  if (!(hmax > 0.0)) throw std::logic_error("neighbour search: support radius must be positive");
  std::array<std::int64_t, D> dims{};
  std::int64_t cells = 1;
  for (int d = 0; d < D; ++d) {
    dims[d] = static_cast<std::int64_t>(std::floor((hi[d] - lo[d]) / hmax)) + 1;
    cells *= dims[d];
  }
  if (cells > 400'000'000) throw std::runtime_error("neighbour search: particles spread over too many cells");

  auto cell_coord = [&](const Vec<D>& p, int d) {
    return std::min<std::int64_t>(dims[d] - 1, static_cast<std::int64_t>((p[d] - lo[d]) / hmax));
  };
  cell_of_.resize(n);
  cell_start_.assign(static_cast<std::size_t>(cells) + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    std::int64_t c = 0;
    for (int d = D - 1; d >= 0; --d) c = c * dims[d] + cell_coord(ps.x[i], d);
    cell_of_[i] = c;
    ++cell_start_[c + 1];
  }
  for (std::int64_t c = 0; c < cells; ++c) cell_start_[c + 1] += cell_start_[c];
  sorted_.resize(n);
  {
    std::vector<std::size_t> fill(cell_start_.begin(), cell_start_.end() - 1);
    for (std::size_t i = 0; i < n; ++i) sorted_[fill[cell_of_[i]]++] = i;  // stable counting sort
  }

  // Visits the candidates of particle i in a fixed order (cells, then index).
  auto for_candidates = [&](std::size_t i, auto&& visit) {
    std::array<std::int64_t, D> c0{};
    for (int d = 0; d < D; ++d) c0[d] = cell_coord(ps.x[i], d);
    std::array<int, D> off;
    off.fill(-1);
    while (true) {
      bool inside = true;
      std::int64_t c = 0;
      for (int d = D - 1; d >= 0; --d) {
        const std::int64_t k = c0[d] + off[d];
        if (k < 0 || k >= dims[d]) { inside = false; break; }
        c = c * dims[d] + k;
      }
      if (inside)
        for (std::size_t s = cell_start_[c]; s < cell_start_[c + 1]; ++s) {
          const std::size_t j = sorted_[s];
          if (are_neighbours((ps.x[i] - ps.x[j]).squaredNorm(), ps.h[i], ps.h[j])) visit(j);
        }
      int d = 0;
      while (d < D && ++off[d] > 1) off[d++] = -1;
      if (d == D) break;
    }
  };

  const auto ni = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < ni; ++i) {
    std::size_t count = 0;
    for_candidates(i, [&count](std::size_t) { ++count; });
    offset_[i + 1] = count;
  }
  for (std::size_t i = 0; i < n; ++i) offset_[i + 1] += offset_[i];
  index_.resize(offset_[n]);
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < ni; ++i) {
    std::size_t k = offset_[i];
    for_candidates(i, [&](std::size_t j) { index_[k++] = static_cast<std::uint32_t>(j); });
  }
}

template <int D>
std::vector<std::vector<std::uint32_t>> brute_force_neighbours(const ParticleSet<D>& ps) {
  std::vector<std::vector<std::uint32_t>> out(ps.size());
  for (std::size_t i = 0; i < ps.size(); ++i)
    for (std::size_t j = 0; j < ps.size(); ++j)
      if (are_neighbours((ps.x[i] - ps.x[j]).squaredNorm(), ps.h[i], ps.h[j]))
        out[i].push_back(static_cast<std::uint32_t>(j));
  return out;
}

template class NeighbourGrid<2>;
template class NeighbourGrid<3>;
template std::vector<std::vector<std::uint32_t>> brute_force_neighbours<2>(const ParticleSet<2>&);
template std::vector<std::vector<std::uint32_t>> brute_force_neighbours<3>(const ParticleSet<3>&);

}  // namespace sc
