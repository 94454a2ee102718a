#include "neighbours/neighbour_grid.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <utility>

namespace sc {

namespace {

inline bool are_neighbours(double r2, double hi, double hj) {
  const double hmax = std::max(hi, hj);
  return r2 <= hmax * hmax;
}

// Binning: particles are sorted in blocks of at least kSortBlock particles, one per thread, while
// the slots are at most kSortSlotsPerParticle times the particles.
constexpr std::size_t kSortBlock = 4096, kSortSlotsPerParticle = 4;
// Slots per part of the parallel prefix sum of the slot sizes.
constexpr std::size_t kPrefixPart = 16384;

// Candidates of the pair search tested at once (GCC/Clang vector extension): four doubles, one
// register, where the target has AVX; two, one SSE2 register, otherwise (a wider vector there would
// be split, and passing it by value changes the ABI, -Wpsabi). The candidate arrays carry
// kLanes − 1 entries of padding after the last particle, so a test may read past the end of a range.
#ifdef __AVX__
constexpr std::size_t kLanes = 4;
#else
constexpr std::size_t kLanes = 2;
#endif
using Lanes = double __attribute__((vector_size(8 * kLanes)));
using LaneMask = std::int64_t __attribute__((vector_size(8 * kLanes)));
inline Lanes load_lanes(const double* p) {
  Lanes v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

}  // namespace

template <int D>
GridBounds<D> NeighbourGrid<D>::bounds(const ParticleSet<D>& ps, std::span<const std::uint32_t> which) {
  double hmax = 0.0, lo[D], hi[D];
  std::fill(lo, lo + D, INFINITY);
  std::fill(hi, hi + D, -INFINITY);
  const auto count = static_cast<std::int64_t>(which.size());
#pragma omp parallel for schedule(static) reduction(max : hmax, hi[:D]) reduction(min : lo[:D])
  for (std::int64_t k = 0; k < count; ++k) {
    const std::uint32_t i = which[k];
    hmax = std::max(hmax, ps.h[i]);
    for (int d = 0; d < D; ++d) {
      lo[d] = std::min(lo[d], ps.x[i][d]);
      hi[d] = std::max(hi[d], ps.x[i][d]);
    }
  }
  Bounds b;
  std::copy(lo, lo + D, b.lo.begin());
  std::copy(hi, hi + D, b.hi.begin());
  b.hmax = hmax;
  return b;
}

template <int D>
bool NeighbourGrid<D>::set_grid(const Bounds& moving, const Bounds& fixed) {
  Bounds all = moving;
  all.merge(fixed);
  const GridGeometry<D> g = GridGeometry<D>::from_bounds(imposed_ ? *imposed_ : all);
  const bool changed = !(g == g_);
  g_ = g;
  return changed;
}

template <int D>
std::uint64_t NeighbourGrid<D>::slot(const ParticleSet<D>& ps, std::size_t i) const {
  return 2 * static_cast<std::uint64_t>(g_.cell_of(ps.x[i])) + inert_[i];
}

template <int D>
void NeighbourGrid<D>::classify(const ParticleSet<D>& ps) {
  const std::size_t n = ps.size();
  if (n >= UINT32_MAX) throw std::runtime_error("neighbour search: too many particles");
  layout_ = ps.layout();
  sorted_.resize(n + kLanes - 1);
  slot_of_.resize(n);
  inert_.resize(n);
  moving_.clear();
  fixed_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    inert_[i] = ps.inert(i);
    (inert_[i] ? fixed_ : moving_).push_back(static_cast<std::uint32_t>(i));
  }
}

template <int D>
void NeighbourGrid<D>::bin(const ParticleSet<D>& ps) {
  classify(ps);
  if (ps.size() == 0) return;
  fixed_bounds_ = bounds(ps, fixed_);
  set_grid(bounds(ps, moving_), fixed_bounds_);
  binned_ = true;
  const auto count = static_cast<std::int64_t>(ps.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < count; ++i) slot_of_[i] = slot(ps, i);
  fixed_id_.resize(fixed_.size());
  fixed_slot_.resize(fixed_.size());
  for (std::size_t k = 0; k < fixed_.size(); ++k) {
    fixed_id_[k] = ps.id[fixed_[k]];
    fixed_slot_[k] = slot_of_[fixed_[k]];
  }
  sort_by_slot(ps);
  mark_cells_near_moving();
}

template <int D>
void NeighbourGrid<D>::bin_moving(const ParticleSet<D>& ps) {
  // A new grid (e.g. of a run resumed from a checkpoint, whose set may carry the same layout
  // count) has no walls cached yet.
  if (ps.size() == 0 || !binned_) return bin(ps);
  if (ps.layout() != layout_) {
    // Particles removed or added (ParticleSet::compact keeps the others' order) or reordered: the
    // walls keep their cells if they are the same ones (ids) in the same order.
    classify(ps);
    if (!std::ranges::equal(fixed_, fixed_id_, {}, [&](std::uint32_t i) { return ps.id[i]; })) return bin(ps);
    for (std::size_t k = 0; k < fixed_.size(); ++k) slot_of_[fixed_[k]] = fixed_slot_[k];
  }
  if (set_grid(bounds(ps, moving_), fixed_bounds_)) return bin(ps);  // the walls' cells moved too
  const auto count = static_cast<std::int64_t>(moving_.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t k = 0; k < count; ++k) slot_of_[moving_[k]] = slot(ps, moving_[k]);
  sort_by_slot(ps);
  mark_cells_near_moving();
}

// Stable counting sort of the particles by slot (sorted_, cx_, ch2_, slot_start_). The particles
// are split into fixed blocks of consecutive indices: each block counts its slots, a slot's range
// is shared out to the blocks in block order, and each block fills its share in index order, so the
// blocks run in parallel and the result is the serial sort's whatever the threads.
template <int D>
void NeighbourGrid<D>::sort_by_slot(const ParticleSet<D>& ps) {
  const std::size_t n = ps.size(), slots = 2 * static_cast<std::size_t>(g_.cells);
  slot_start_.resize(slots + 2);
  // One block per thread, of at least kSortBlock particles; one block if the blocks' counts would
  // outweigh the particles by far.
  const auto threads = static_cast<std::size_t>(omp_get_max_threads());
  const auto blocks = static_cast<std::int64_t>(
      slots > kSortSlotsPerParticle * n ? 1 : std::clamp<std::size_t>(n / kSortBlock, 1, threads));
  auto block_range = [&](std::int64_t b) { return std::pair{b * n / blocks, (b + 1) * n / blocks}; };
  block_count_.resize(blocks * slots);
#pragma omp parallel for schedule(static)
  for (std::int64_t b = 0; b < blocks; ++b) {
    std::uint32_t* count = block_count_.data() + b * slots;
    std::fill(count, count + slots, 0);
    const auto [first, last] = block_range(b);
    for (std::size_t i = first; i < last; ++i) ++count[slot_of_[i]];
  }
  // Each block's count becomes the start of its share within the slot, and slot_start_ the
  // prefix sum of the slots' sizes, in two parallel passes over fixed parts of the slots: each
  // part's own prefix sum, then the parts' starts added (integers: exact, any threads).
  const auto parts = static_cast<std::int64_t>((slots + kPrefixPart - 1) / kPrefixPart);
  auto part_range = [&](std::int64_t q) { return std::pair{q * kPrefixPart, std::min(slots, (q + 1) * kPrefixPart)}; };
  part_start_.resize(parts + 1);
#pragma omp parallel for schedule(static)
  for (std::int64_t q = 0; q < parts; ++q) {
    std::uint32_t start = 0;
    const auto [first, last] = part_range(q);
    for (std::size_t s = first; s < last; ++s) {
      slot_start_[s] = start;
      for (std::int64_t b = 0; b < blocks; ++b) start += std::exchange(block_count_[b * slots + s], start - slot_start_[s]);
    }
    part_start_[q + 1] = start;
  }
  part_start_[0] = 0;
  for (std::int64_t q = 0; q < parts; ++q) part_start_[q + 1] += part_start_[q];
#pragma omp parallel for schedule(static)
  for (std::int64_t q = 1; q < parts; ++q) {
    const auto [first, last] = part_range(q);
    for (std::size_t s = first; s < last; ++s) slot_start_[s] += part_start_[q];
  }
  slot_start_[slots] = slot_start_[slots + 1] = static_cast<std::uint32_t>(n);
  for (auto& c : cx_) {  // the particles' entries are written below
    c.resize(n + kLanes - 1);
    std::fill(c.begin() + n, c.end(), 0.0);  // the padding
  }
  ch2_.resize(n + kLanes - 1);
  std::fill(ch2_.begin() + n, ch2_.end(), 0.0);
  std::fill(sorted_.begin() + n, sorted_.end(), 0);
#pragma omp parallel for schedule(static)
  for (std::int64_t b = 0; b < blocks; ++b) {
    std::uint32_t* fill = block_count_.data() + b * slots;
    const auto [first, last] = block_range(b);
    for (std::size_t i = first; i < last; ++i) {
      const std::uint32_t k = slot_start_[slot_of_[i]] + fill[slot_of_[i]]++;
      sorted_[k] = static_cast<std::uint32_t>(i);
      for (int d = 0; d < D; ++d) cx_[d][k] = ps.x[i][d];
      ch2_[k] = ps.h[i] * ps.h[i];
    }
  }
}

// near_moving_[c]: a non-inert particle lies in the 3^D block of cells around c. One pass per
// dimension, each widening the mark by one cell along it: a cell's mark is ORed with those of the
// cells before and after it along the dimension, as whole runs of cells (vectorised).
template <int D>
void NeighbourGrid<D>::mark_cells_near_moving() {
  near_moving_.resize(g_.cells);
  spread_.resize(g_.cells);
#pragma omp parallel for schedule(static)
  for (std::int64_t c = 0; c < g_.cells; ++c) near_moving_[c] = slot_start_[2 * c + 1] > slot_start_[2 * c];
  std::int64_t stride = 1;  // cells between neighbours along dimension d
  for (int d = 0; d < D; ++d) {
    // Lines along d: `lines` of them, each of g_.dims[d] runs of `run` cells (stride apart).
    const std::int64_t run = d == 0 ? 1 : stride, lines = g_.cells / (run * g_.dims[d]);
    const std::uint8_t* from = near_moving_.data();
    std::uint8_t* to = spread_.data();
    if (d == 0) {
#pragma omp parallel for schedule(static)
      for (std::int64_t l = 0; l < lines; ++l) {
        const std::uint8_t* a = from + l * g_.dims[0];
        std::uint8_t* b = to + l * g_.dims[0];
        const std::int64_t last = g_.dims[0] - 1;
        b[0] = a[0] | (last > 0 && a[1]);
        for (std::int64_t k = 1; k < last; ++k) b[k] = a[k - 1] | a[k] | a[k + 1];
        if (last > 0) b[last] = a[last - 1] | a[last];
      }
    } else {
      const std::int64_t rows = lines * g_.dims[d];
#pragma omp parallel for schedule(static)
      for (std::int64_t r = 0; r < rows; ++r) {  // run k of line l
        const std::int64_t k = r % g_.dims[d];
        const std::uint8_t* a = from + r * run;
        const std::uint8_t* before = k > 0 ? a - run : a;
        const std::uint8_t* after = k + 1 < g_.dims[d] ? a + run : a;
        std::uint8_t* b = to + r * run;
        for (std::int64_t j = 0; j < run; ++j) b[j] = before[j] | a[j] | after[j];
      }
    }
    near_moving_.swap(spread_);
    stride *= g_.dims[d];
  }
}

// Scans the rows of 3 cells along x around particle i's cell in a fixed order (rows, then x), so
// the list comes out ordered by cell. A non-inert particle scans each row as one range of sorted_
// (the cells of a row are adjacent there); an inert one only the non-inert part of each cell.
// Rows and end cells farther from x_i than the cell size (a bound on every pair's support) hold
// no neighbour and are skipped, which leaves the list unchanged. The scan tests two candidates at
// a time, writes every candidate and advances past it only if it is a neighbour (no branch to
// mispredict), into room reserved in `out` for all candidates after its first `used` entries;
// returns the entries used then. find_pairs does not call it for an inert particle with no non-inert
// particle in its 3^D block of cells (near_moving_), whose list is empty.
template <int D>
std::size_t NeighbourGrid<D>::append_neighbours(const ParticleSet<D>& ps, std::size_t i, std::vector<std::uint32_t>& out,
                                                std::size_t used) const {
  const Vec<D> xi = ps.x[i];
  const double hi2 = ps.h[i] * ps.h[i];
  std::array<std::int64_t, D> c0{};
  std::array<std::array<double, 3>, D> gap2{};  // squared distance from x_i to the cells at offset -1, 0, +1
  for (int d = 0; d < D; ++d) {
    c0[d] = g_.coord(xi, d);
    const double below = std::max(0.0, xi[d] - (g_.lo[d] + c0[d] * g_.cell));
    const double above = std::max(0.0, g_.lo[d] + (c0[d] + 1) * g_.cell - xi[d]);
    gap2[d] = {below * below, 0.0, above * above};
  }
  // Reach with a margin far above the rounding of the cell bounds, so no neighbour is ever cut.
  const double reach2 = (g_.cell * (1.0 + 1e-6)) * (g_.cell * (1.0 + 1e-6));
  std::array<std::uint32_t, 27> begin, end;  // ranges of candidates in sorted_, filled before use
  std::size_t ranges = 0, candidates = 0;
  auto add_range = [&](std::uint32_t b, std::uint32_t e) {
    begin[ranges] = b;
    end[ranges++] = e;
    candidates += e - b;
  };
  std::array<int, D> off;
  off.fill(-1);
  while (true) {
    bool inside = true;
    std::int64_t row = 0;  // linear index of the row's cell at x = 0
    double row_gap2 = 0.0;
    for (int d = D - 1; d >= 1; --d) {
      const std::int64_t k = c0[d] + off[d];
      if (k < 0 || k >= g_.dims[d]) { inside = false; break; }
      row = row * g_.dims[d] + k;
      row_gap2 += gap2[d][off[d] + 1];
    }
    if (inside && row_gap2 <= reach2) {
      const std::int64_t x_first = c0[0] > 0 && row_gap2 + gap2[0][0] <= reach2 ? c0[0] - 1 : c0[0];
      const std::int64_t x_last = c0[0] + 1 < g_.dims[0] && row_gap2 + gap2[0][2] <= reach2 ? c0[0] + 1 : c0[0];
      row *= g_.dims[0];
      if (!inert_[i])
        add_range(slot_start_[2 * (row + x_first)], slot_start_[2 * (row + x_last) + 2]);
      else
        for (std::int64_t c = row + x_first; c <= row + x_last; ++c) add_range(slot_start_[2 * c], slot_start_[2 * c + 1]);
    }
    int d = 1;
    while (d < D && ++off[d] > 1) off[d++] = -1;
    if (d == D) break;
  }
  if (out.size() < used + candidates + 1) out.resize(std::max(2 * out.size(), used + candidates + 1));
  std::array<Lanes, D> xi_lanes;
  for (int d = 0; d < D; ++d) xi_lanes[d] = Lanes{} + xi[d];
  const Lanes hi2_lanes = Lanes{} + hi2;
  // Candidates k .. k + kLanes − 1: |x_i − x_k|² summed as Eigen's squaredNorm sums it, and
  // r² <= max(h_i², h_k²) tested as (r² <= h_i²) | (r² <= h_k²), so the lists are those of the
  // scalar test. A lane that is a neighbour is -1.
  auto test_lanes = [&](std::size_t k) {
    Lanes dx = xi_lanes[0] - load_lanes(cx_[0].data() + k);
    Lanes r2 = dx * dx;
    for (int d = 1; d < D; ++d) {
      dx = xi_lanes[d] - load_lanes(cx_[d].data() + k);
      r2 += dx * dx;
    }
    return LaneMask((r2 <= hi2_lanes) | (r2 <= load_lanes(ch2_.data() + k)));
  };
  // Each candidate is written at the list's end, which advances when it is a neighbour.
  std::uint32_t* list = out.data();
  for (std::size_t r = 0; r < ranges; ++r) {
    std::size_t k = begin[r];
    for (; k + kLanes <= end[r]; k += kLanes) {
      const LaneMask near = test_lanes(k);
      for (std::size_t l = 0; l < kLanes; ++l) {
        list[used] = sorted_[k + l];
        used -= near[l];
      }
    }
    if (k < end[r]) {  // the range's last candidates (the other lanes read past them)
      const LaneMask near = test_lanes(k);
      for (std::size_t l = 0; k + l < end[r]; ++l) {
        list[used] = sorted_[k + l];
        used -= near[l];
      }
    }
  }
  return used;
}

template <int D>
const std::vector<std::size_t>& NeighbourGrid<D>::storage_order() {
  storage_order_.clear();
  const std::span<const std::uint32_t> sorted(sorted_.data(), std::max(sorted_.size(), kLanes - 1) - (kLanes - 1));  // no padding
  for (const std::uint32_t i : sorted)
    if (!inert_[i]) storage_order_.push_back(i);
  for (const std::uint32_t i : sorted)
    if (inert_[i]) storage_order_.push_back(i);
  return storage_order_;
}

template <int D>
void NeighbourGrid<D>::find_pairs(const ParticleSet<D>& ps) {
  const std::size_t n = ps.size();
  offset_.resize(n + 1);  // every entry is written below
  offset_[0] = 0;
  if (n == 0) {
    chunk_base_.assign(1, 0);
    return;
  }
  const auto chunks = static_cast<std::int64_t>((n + kChunk - 1) / kChunk);
  chunk_lists_.resize(chunks);
  chunk_used_.resize(chunks);
#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t c = 0; c < chunks; ++c) {
    std::size_t used = 0;
    const std::size_t end = std::min(n, (c + 1) * kChunk);
    for (std::size_t i = c * kChunk; i < end; ++i) {
      if (i < listed_ && (!inert_[i] || near_moving_[slot_of_[i] / 2]))  // else no non-inert particle within reach: an empty list
        used = append_neighbours(ps, i, chunk_lists_[c], used);
      offset_[i + 1] = used;
    }
    chunk_used_[c] = used;
  }
  // Per-chunk end positions -> global offsets.
  chunk_base_.resize(chunks + 1);
  chunk_base_[0] = 0;
  for (std::int64_t c = 0; c < chunks; ++c) chunk_base_[c + 1] = chunk_base_[c] + chunk_used_[c];
#pragma omp parallel for schedule(static)
  for (std::int64_t c = 0; c < chunks; ++c) {
    const std::size_t end = std::min(n, (c + 1) * kChunk);
    for (std::size_t i = c * kChunk; i < end; ++i) offset_[i + 1] += chunk_base_[c];
  }
}

template <int D>
std::vector<std::vector<std::uint32_t>> brute_force_neighbours(const ParticleSet<D>& ps) {
  std::vector<std::vector<std::uint32_t>> out(ps.size());
  for (std::size_t i = 0; i < ps.size(); ++i)
    for (std::size_t j = 0; j < ps.size(); ++j)
      if (!(ps.inert(i) && ps.inert(j)) && are_neighbours((ps.x[i] - ps.x[j]).squaredNorm(), ps.h[i], ps.h[j]))
        out[i].push_back(static_cast<std::uint32_t>(j));
  return out;
}

template class NeighbourGrid<2>;
template class NeighbourGrid<3>;
template std::vector<std::vector<std::uint32_t>> brute_force_neighbours<2>(const ParticleSet<2>&);
template std::vector<std::vector<std::uint32_t>> brute_force_neighbours<3>(const ParticleSet<3>&);

}  // namespace sc
