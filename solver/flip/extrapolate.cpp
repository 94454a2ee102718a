#include "flip/extrapolate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

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

/// The distance φ per face of component a in cell widths, capped at `far`: 0 on the faces next to
/// a fluid cell, `wall` on the tank's wall faces, within `box` by fast sweeping, `far` outside it.
template <int D>
std::vector<double> face_distance(const MacGrid<D>& grid, const std::vector<Cell>& label, int a, const IndexBox<D>& box,
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
  for (unsigned order = 0; order < (1u << D); ++order)
    box.sweep(order, [&](const Index<D>& f, long k) {
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
  return phi;
}

/// u = Σ_d w_d u_d / Σ_d w_d on the faces of 0 < φ ≤ layers, in the 2^D sweep orders, then 0 on the
/// faces of φ > layers.
template <int D>
void extend(const IndexBox<D>& box, const std::vector<double>& phi, double layers, std::vector<double>& u) {
  box.sweep(0, [&](const Index<D>&, long k) {
    if (phi[k] > 0.0) u[k] = 0.0;
  });
  for (unsigned order = 0; order < (1u << D); ++order)
    box.sweep(order, [&](const Index<D>& f, long k) {
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
    const std::vector<double> phi = face_distance<D>(grid, label, a, box, far);
    for (FaceField<D>* u : fields) extend<D>(box, phi, layers, (*u)[a]);
  }
}

template void extrapolate<2>(const MacGrid<2>&, const std::vector<Cell>&, int, std::span<FaceField<2>* const>);
template void extrapolate<3>(const MacGrid<3>&, const std::vector<Cell>&, int, std::span<FaceField<3>* const>);

}  // namespace sc::flip
