#include "flip/extrapolate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace sc::flip {

namespace {

constexpr double wall = -1.0;  // φ of a wall face: no source, never changed

/// Godunov upwind solution of |∇φ| = 1 (unit spacing) from the smallest neighbour value per axis.
template <int D>
double eikonal(std::array<double, D> m) {
  for (int i = 1; i < D; ++i)  // insertion sort: D is at most 3
    for (int j = i; j > 0 && m[j - 1] > m[j]; --j) std::swap(m[j - 1], m[j]);
  double phi = m[0] + 1.0;
  double sum = m[0], sum2 = m[0] * m[0];
  for (int j = 1; j < D && phi > m[j]; ++j) {
    sum += m[j];
    sum2 += m[j] * m[j];
    const double n = j + 1.0;
    phi = (sum + std::sqrt(std::max(0.0, sum * sum - n * (sum2 - 1.0)))) / n;
  }
  return phi;
}

/// φ per face of component a at the start of the sweeps: 0 on the faces next to a fluid cell,
/// `wall` on the tank's wall faces, `far` elsewhere.
template <int D>
std::vector<double> sources(const MacGrid<D>& grid, const std::vector<Cell>& label, int a, const IndexBox<D>& box,
                            double far) {
  std::vector<double> phi(grid.face_count(a), far);
  const Index<D> dims = grid.face_dims(a);
  for (const int side : {0, dims[a] - 1}) {
    Index<D> lo{}, hi = dims;
    for (int d = 0; d < D; ++d) --hi[d];
    lo[a] = hi[a] = side;
    IndexBox<D>(dims, lo, hi).sweep(0, [&](const Index<D>&, long k) { phi[k] = wall; });
  }
  box.sweep(0, [&](const Index<D>& f, long k) {
    if (phi[k] == wall) return;
    Index<D> below = f;
    --below[a];
    if (is_fluid(label[grid.cell(f)]) || is_fluid(label[grid.cell(below)])) phi[k] = 0.0;
  });
  return phi;
}

/// The faces of a box within `reach` steps along every axis of a face of φ = 0, as one span along
/// axis 0 per row of faces: each update of a sweep adds at least 1/√D to the smallest neighbour φ,
/// so a face further than far·√D steps from every source keeps φ = far and the sweeps need not
/// visit it.
template <int D>
class Band {
 public:
  Band(const IndexBox<D>& box, const std::vector<double>& phi, int reach) : box_(box), rows_(box) {
    rows_.hi[0] = rows_.lo[0];
    span_.assign(MacGrid<D>::count(box.dims) / box.dims[0], {box.hi[0] + 1, box.lo[0] - 1});
    box.sweep(0, [&](const Index<D>& f, long k) {
      if (phi[k] != 0.0) return;
      Span& s = span_[k / box.dims[0]];
      s = {std::min(s[0], std::max(box.lo[0], f[0] - reach)), std::max(s[1], std::min(box.hi[0], f[0] + reach))};
    });
    for (int d = 1; d < D; ++d) widen(d, reach);
  }

  /// body(f, k) for the faces of the band in the sweep order `order` (IndexBox::sweep).
  template <class Body>
  void sweep(unsigned order, Body&& body) const {
    rows_.sweep(order, [&](const Index<D>& row, std::size_t k0) {
      const auto [first, last] = span_[k0 / box_.dims[0]];
      Index<D> f = row;
      for (int j = 0; j <= last - first; ++j) {
        f[0] = order & 1 ? last - j : first + j;
        body(std::as_const(f), static_cast<long>(k0) + f[0] - box_.lo[0]);
      }
    });
  }
  const IndexBox<D>& box() const { return box_; }

 private:
  using Span = std::array<int, 2>;  // first, last along axis 0; empty when first > last

  /// Each row's span becomes the hull of the spans of the rows within `reach` along axis d.
  void widen(int d, int reach) {
    const std::vector<Span> narrow = span_;
    const long stride = box_.stride[d] / box_.dims[0];
    rows_.sweep(0, [&](const Index<D>& row, std::size_t k0) {
      Span& s = span_[k0 / box_.dims[0]];
      for (int o = std::max(box_.lo[d], row[d] - reach); o <= std::min(box_.hi[d], row[d] + reach); ++o) {
        const Span& n = narrow[static_cast<long>(k0 / box_.dims[0]) + (o - row[d]) * stride];
        s = {std::min(s[0], n[0]), std::max(s[1], n[1])};
      }
    });
  }

  IndexBox<D> box_, rows_;  // rows_: the box with one index along axis 0
  std::vector<Span> span_;  // per row of faces of the grid (flat index / dims[0])
};

/// The distance φ in cell widths from the faces of φ = 0, capped at `far`, by fast sweeping of the
/// band.
template <int D>
void sweep_distance(const Band<D>& band, double far, std::vector<double>& phi) {
  const IndexBox<D>& box = band.box();
  for (unsigned order = 0; order < (1u << D); ++order)
    band.sweep(order, [&](const Index<D>& f, long k) {
      if (phi[k] <= 0.0) return;
      std::array<double, D> m{};
      double nearest = far;
      for (int d = 0; d < D; ++d) {
        m[d] = far;
        if (f[d] > box.lo[d] && phi[k - box.stride[d]] >= 0.0) m[d] = std::min(m[d], phi[k - box.stride[d]]);
        if (f[d] < box.hi[d] && phi[k + box.stride[d]] >= 0.0) m[d] = std::min(m[d], phi[k + box.stride[d]]);
        nearest = std::min(nearest, m[d]);
      }
      if (nearest < phi[k]) phi[k] = std::min({phi[k], eikonal<D>(m), far});  // else φ > nearest: no change
    });
}

/// u = Σ_d w_d u_d / Σ_d w_d on the faces of 0 < φ ≤ layers, in the 2^D sweep orders, then 0 on the
/// faces of φ > layers.
template <int D>
void extend(const Band<D>& band, const std::vector<double>& phi, double layers, std::vector<double>& u) {
  const IndexBox<D>& box = band.box();
  band.sweep(0, [&](const Index<D>&, long k) {
    if (phi[k] > 0.0) u[k] = 0.0;
  });
  for (unsigned order = 0; order < (1u << D); ++order)
    band.sweep(order, [&](const Index<D>& f, long k) {
      if (phi[k] <= 0.0 || phi[k] > layers) return;
      double sum = 0.0, weight = 0.0;
      for (int d = 0; d < D; ++d) {
        long up = -1;  // the neighbour of smaller φ along d (the lower one on a tie)
        if (f[d] > box.lo[d] && phi[k - box.stride[d]] >= 0.0) up = k - box.stride[d];
        if (f[d] < box.hi[d] && phi[k + box.stride[d]] >= 0.0 && (up < 0 || phi[k + box.stride[d]] < phi[up]))
          up = k + box.stride[d];
        if (up < 0 || phi[up] >= phi[k]) continue;
        sum += (phi[k] - phi[up]) * u[up];
        weight += phi[k] - phi[up];
      }
      if (weight > 0.0) u[k] = sum / weight;
    });
  for (std::size_t k = 0; k < u.size(); ++k)
    if (phi[k] > layers) u[k] = 0.0;
}

}  // namespace

template <int D>
void extrapolate(const MacGrid<D>& grid, const std::vector<Cell>& label, int layers,
                 std::span<FaceField<D>* const> fields) {
  const IndexBox<D> fluid = IndexBox<D>::around(grid.n, [&](std::size_t k) { return is_fluid(label[k]); });
  const double far = layers + 1.0;
#pragma omp parallel for schedule(dynamic, 1)
  for (int a = 0; a < D; ++a) {
    const Index<D> dims = grid.face_dims(a);
    Index<D> lo{}, hi{};
    for (int d = 0; d < D; ++d) {
      lo[d] = std::max(0, fluid.lo[d] - layers - 1);
      hi[d] = std::min(dims[d] - 1, fluid.hi[d] + (d == a ? 1 : 0) + layers + 1);
    }
    const IndexBox<D> box(dims, lo, hi);
    std::vector<double> phi = sources<D>(grid, label, a, box, far);
    const Band<D> band(box, phi, static_cast<int>(std::ceil(far * std::sqrt(static_cast<double>(D)))));
    sweep_distance<D>(band, far, phi);
    for (FaceField<D>* u : fields) extend<D>(band, phi, layers, (*u)[a]);
  }
}

template void extrapolate<2>(const MacGrid<2>&, const std::vector<Cell>&, int, std::span<FaceField<2>* const>);
template void extrapolate<3>(const MacGrid<3>&, const std::vector<Cell>&, int, std::span<FaceField<3>* const>);

}  // namespace sc::flip
