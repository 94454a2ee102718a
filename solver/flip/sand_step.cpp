#include "flip/sand_step.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "sand/frictional_stress.hpp"
#include "sand/yield.hpp"

namespace sc::flip {

namespace {

template <int D>
Index<D> shifted(Index<D> c, int axis, int by) {
  c[axis] += by;
  return c;
}

template <int D>
bool fluid_at(const MacGrid<D>& grid, const CellState<D>& cells, const Index<D>& c) {
  return MacGrid<D>::inside(c, grid.n) && is_fluid(cells.label[grid.cell(c)]);
}

/// u_a at the centre of cell c: the mean of its two a-faces.
template <int D>
double centred(const MacGrid<D>& grid, const FaceField<D>& u, int a, const Index<D>& c) {
  return 0.5 * (u[a][grid.face(a, c)] + u[a][grid.face(a, shifted<D>(c, a, 1))]);
}

/// ∂u_a/∂x_b (b ≠ a) at the centre of cell c.
template <int D>
double cross_derivative(const MacGrid<D>& grid, const CellState<D>& cells, const FaceField<D>& u, int a, int b,
                        const Index<D>& c) {
  const Index<D> lo = shifted<D>(c, b, -1), hi = shifted<D>(c, b, 1);
  const bool fl = fluid_at<D>(grid, cells, lo), fh = fluid_at<D>(grid, cells, hi);
  if (fl && fh) return (centred<D>(grid, u, a, hi) - centred<D>(grid, u, a, lo)) / (2.0 * grid.dx);
  if (fh) return (centred<D>(grid, u, a, hi) - centred<D>(grid, u, a, c)) / grid.dx;
  if (fl) return (centred<D>(grid, u, a, c) - centred<D>(grid, u, a, lo)) / grid.dx;
  return 0.0;
}

}  // namespace

template <int D>
Mat<D> cell_strain_rate(const MacGrid<D>& grid, const CellState<D>& cells, const FaceField<D>& u, const Index<D>& c) {
  Mat<D> G;
  for (int a = 0; a < D; ++a)
    for (int b = 0; b < D; ++b)
      G(a, b) = a == b ? (u[a][grid.face(a, shifted<D>(c, a, 1))] - u[a][grid.face(a, c)]) / grid.dx
                       : cross_derivative<D>(grid, cells, u, a, b, c);
  return 0.5 * (G + G.transpose());
}

template <int D>
void classify_sand(const MacGrid<D>& grid, const CellState<D>& cells, const FaceField<D>& u,
                   const std::vector<double>& p, const SandParams& sand, double dt, SandCells<D>& out) {
  const std::size_t n = grid.cell_count();
  out.yielding.assign(n, 0);
  out.rigid.assign(n, 0);
  out.stress.resize(n);
  const double sin_phi = sand.sin_phi(), strength = yield_strength_factor(sand.yield_surface);
  const IndexBox<D> box = IndexBox<D>::around(grid.n, [&](std::size_t k) { return cells.label[k] == Cell::Sand; });
  box.parallel_for_each([&](const Index<D>& c, std::size_t k) {
    if (cells.label[k] != Cell::Sand) return;
    const Mat<D> strain = cell_strain_rate<D>(grid, cells, u, c);
    const Mat<D> sigma_rigid = rigid_stress<D>(strain, cells.density[k], grid.dx, dt);
    if (is_rigid<D>(sigma_rigid, p[k], sin_phi, sand.cohesion, strength)) {
      out.rigid[k] = 1;
    } else {
      out.yielding[k] = 1;
      out.stress[k] = -frictional_stress<D>(strain, p[k], sin_phi);
    }
  });
}

template <int D>
void apply_frictional_stress(const MacGrid<D>& grid, const CellState<D>& cells, const SandCells<D>& sand_cells,
                             double dt, FaceField<D>& u) {
  const auto tau = [&](const Index<D>& c, int a, int b) {
    if (!MacGrid<D>::inside(c, grid.n)) return 0.0;
    const std::size_t k = grid.cell(c);
    return sand_cells.yielding[k] ? sand_cells.stress[k](a, b) : 0.0;
  };
  const auto sand_at = [&](const Index<D>& c) {
    return MacGrid<D>::inside(c, grid.n) && cells.label[grid.cell(c)] == Cell::Sand;
  };
  const IndexBox<D> flowing = IndexBox<D>::around(grid.n, [&](std::size_t k) { return sand_cells.yielding[k] != 0; });
  for (int a = 0; a < D; ++a) {
    flowing.faces(a).parallel_for_each([&](const Index<D>& c1, std::size_t k) {
      if (grid.is_wall_face(a, c1)) return;
      const Index<D> c0 = shifted<D>(c1, a, -1);
      if (!sand_cells.yielding[grid.cell(c0)] && !sand_cells.yielding[grid.cell(c1)]) return;
      double div = (tau(c1, a, a) - tau(c0, a, a)) / grid.dx;
      for (int b = 0; b < D; ++b) {
        if (b == a) continue;
        const auto edge = [&](int s) {
          const Index<D> d0 = shifted<D>(c0, b, s), d1 = shifted<D>(c1, b, s);
          if (!sand_at(c0) || !sand_at(c1) || !sand_at(d0) || !sand_at(d1)) return 0.0;  // boundary: no traction
          return 0.25 * (tau(c0, a, b) + tau(c1, a, b) + tau(d0, a, b) + tau(d1, a, b));
        };
        div += (edge(1) - edge(-1)) / grid.dx;
      }
      u[a][k] += dt / face_density<D>(grid, cells, a, c1) * div;
    });
  }
}

template <int D>
double wall_normal_stress(const MacGrid<D>& grid, const CellState<D>& cells, const std::vector<double>& p,
                          const FaceField<D>& before, double dt, int a, int side, const Index<D>& c) {
  const std::size_t k = grid.cell(c);
  const double into_wall = side ? before[a][grid.face(a, shifted<D>(c, a, 1))] : -before[a][grid.face(a, c)];
  return std::max(0.0, p[k]) + cells.density[k] * grid.dx / (2.0 * dt) * std::max(0.0, into_wall);
}

template <int D>
void wall_friction(const MacGrid<D>& grid, const CellState<D>& cells, const SandCells<D>& sand_cells,
                   const std::vector<double>& p, const FaceField<D>& before, const SideFriction<D>& mu_side, double dt,
                   FaceField<D>& u) {
  for (int a = 0; a < D; ++a)
    for (const int side : {0, 1})
      for (int b = 0; b < D; ++b) {
        const double mu = mu_side[2 * a + side];
        if (b == a || mu <= 0.0) continue;
        const Index<D> dims = grid.face_dims(b);
        Index<D> lo{}, hi = dims;
        for (int d = 0; d < D; ++d) --hi[d];
        lo[a] = hi[a] = side ? grid.n[a] - 1 : 0;  // the cell layer next to the wall
        IndexBox<D>(dims, lo, hi).sweep(0, [&](const Index<D>& c1, std::size_t k) {
          if (grid.is_wall_face(b, c1)) return;
          const Index<D> c0 = shifted<D>(c1, b, -1);
          if (!sand_cells.yielding[grid.cell(c0)] && !sand_cells.yielding[grid.cell(c1)]) return;
          const double stress = 0.5 * (wall_normal_stress<D>(grid, cells, p, before, dt, a, side, c0) +
                                       wall_normal_stress<D>(grid, cells, p, before, dt, a, side, c1));
          const double bound = mu * stress * dt / (face_density<D>(grid, cells, b, c1) * grid.dx);
          const double speed = std::abs(u[b][k]);
          u[b][k] = speed > bound ? u[b][k] * (1.0 - bound / speed) : 0.0;
        });
      }
}

template <int D>
std::vector<std::vector<std::size_t>> rigid_groups(const MacGrid<D>& grid, const std::vector<std::uint8_t>& rigid) {
  std::vector<std::vector<std::size_t>> groups;
  std::vector<std::uint8_t> seen(rigid.size(), 0);
  for (std::size_t seed = 0; seed < rigid.size(); ++seed) {
    if (!rigid[seed] || seen[seed]) continue;
    std::vector<std::size_t> group{seed};
    seen[seed] = 1;
    for (std::size_t head = 0; head < group.size(); ++head) {
      const Index<D> c = MacGrid<D>::unflat(group[head], grid.n);
      for (int a = 0; a < D; ++a)
        for (const int s : {-1, 1}) {
          const Index<D> nb = shifted<D>(c, a, s);
          if (!MacGrid<D>::inside(nb, grid.n)) continue;
          const std::size_t k = grid.cell(nb);
          if (rigid[k] && !seen[k]) {
            seen[k] = 1;
            group.push_back(k);
          }
        }
    }
    groups.push_back(std::move(group));
  }
  return groups;
}

template <int D>
std::vector<GroupFace> group_faces(const MacGrid<D>& grid, const CellState<D>& cells,
                                   const std::vector<std::size_t>& group) {
  // In flat cell order, both the lower and the upper a-faces of the cells are in flat face order:
  // merging the two lists visits each face once, in face order, with the cells on either side.
  std::vector<std::size_t> sorted = group;
  std::sort(sorted.begin(), sorted.end());
  const std::size_t n = sorted.size();
  const double volume = std::pow(grid.dx, D);
  std::vector<GroupFace> out;
  out.reserve(D * (n + 1));
  std::vector<std::size_t> lower(n), upper(n);
  for (int a = 0; a < D; ++a) {
    for (std::size_t j = 0; j < n; ++j) {
      const Index<D> c = MacGrid<D>::unflat(sorted[j], grid.n);
      lower[j] = grid.face(a, c);
      upper[j] = grid.face(a, shifted<D>(c, a, 1));
    }
    for (std::size_t l = 0, u = 0; l < n || u < n;) {
      const std::size_t f = std::min(l < n ? lower[l] : SIZE_MAX, u < n ? upper[u] : SIZE_MAX);
      double mass = 0.0;  // ρ Δx^D / 2 of the cell above, then of the cell below
      if (l < n && lower[l] == f) mass += 0.5 * cells.density[sorted[l++]] * volume;
      if (u < n && upper[u] == f) mass += 0.5 * cells.density[sorted[u++]] * volume;
      out.push_back({a, f, mass, grid.is_wall_face(a, MacGrid<D>::unflat(f, grid.face_dims(a)))});
    }
  }
  return out;
}

template <int D>
RigidFit<D> fit_rigid_motion(const MacGrid<D>& grid, const std::vector<GroupFace>& faces, const Vec<D>& centre,
                             const FaceField<D>& u) {
  constexpr int K = D + angular_dim<D>;
  Eigen::Matrix<double, K, K> A = Eigen::Matrix<double, K, K>::Zero();
  Eigen::Matrix<double, K, 1> b = Eigen::Matrix<double, K, 1>::Zero();
  for (const auto& f : faces) {
    const Vec<D> r = grid.face_centre(f.axis, MacGrid<D>::unflat(f.index, grid.face_dims(f.axis))) - centre;
    const Vec<D> e = Vec<D>::Unit(f.axis);
    Eigen::Matrix<double, K, 1> J;  // fixed-size halves: GCC 12 warns (-Warray-bounds) on the comma initialiser's AVX path
    J.template head<D>() = e;
    J.template tail<angular_dim<D>>() = moment<D>(r, e);
    A += f.mass * J * J.transpose();
    b += f.mass * u[f.axis][f.index] * J;
  }
  // The right-hand side of dynamic size: with a fixed 3-vector (D = 2), GCC 12 warns (-Warray-bounds)
  // on a 4-wide AVX load in Eigen's triangular solve, a branch taken only for 4 or more rows.
  const Eigen::VectorXd q = Eigen::CompleteOrthogonalDecomposition<Eigen::Matrix<double, K, K>>(A).solve(Eigen::VectorXd(b));
  RigidFit<D> fit;
  fit.centre = centre;
  fit.velocity = q.template head<D>();
  fit.omega = q.template tail<angular_dim<D>>();
  return fit;
}

template <int D>
void group_wall_friction(const MacGrid<D>& grid, const std::vector<std::size_t>& group,
                         const std::vector<GroupFace>& faces, const RigidFit<D>& before,
                         const SideFriction<D>& mu_side, RigidFit<D>& fit) {
  Vec<D> axis_mass = Vec<D>::Zero();  // Σ m_f per velocity component: P_b = M_b v_b
  for (const auto& f : faces) axis_mass[f.axis] += f.mass;
  for (int a = 0; a < D; ++a)
    for (const int side : {0, 1}) {
      const int layer = side ? grid.n[a] - 1 : 0;
      const bool touches = std::any_of(group.begin(), group.end(),
                                       [&](std::size_t k) { return MacGrid<D>::unflat(k, grid.n)[a] == layer; });
      if (!touches) continue;
      const double inward = side ? -1.0 : 1.0;  // the wall's normal, into the tank
      const double away = std::max(0.0, inward * fit.velocity[a]);  // no penetration of the rigid group
      fit.velocity[a] = inward * away;
      const double pushed = away - inward * before.velocity[a], mu = mu_side[2 * a + side];
      if (pushed <= 0.0 || mu <= 0.0) continue;
      const double impulse = axis_mass[a] * pushed;  // normal impulse of this wall on the group [N s]
      Vec<D> tangential = axis_mass.cwiseProduct(fit.velocity);
      tangential[a] = 0.0;
      const double P = tangential.norm();
      if (P <= mu * impulse) {
        fit.velocity.setZero();
        fit.omega.setZero();
        return;
      }
      for (int b = 0; b < D; ++b)
        if (b != a) fit.velocity[b] -= mu * impulse * fit.velocity[b] / P;
    }
}

template <int D>
void apply_rigid_motion(const MacGrid<D>& grid, const std::vector<GroupFace>& faces, const RigidFit<D>& fit,
                        FaceField<D>& u) {
  for (const auto& f : faces) {
    if (f.wall) continue;
    const Vec<D> r = grid.face_centre(f.axis, MacGrid<D>::unflat(f.index, grid.face_dims(f.axis))) - fit.centre;
    u[f.axis][f.index] = fit.velocity[f.axis] + spin_velocity<D>(fit.omega, r)[f.axis];
  }
}

#define SC_FLIP_SAND(D)                                                                                            \
  template Mat<D> cell_strain_rate<D>(const MacGrid<D>&, const CellState<D>&, const FaceField<D>&, const Index<D>&); \
  template void classify_sand<D>(const MacGrid<D>&, const CellState<D>&, const FaceField<D>&,                     \
                                 const std::vector<double>&, const SandParams&, double, SandCells<D>&);            \
  template void apply_frictional_stress<D>(const MacGrid<D>&, const CellState<D>&, const SandCells<D>&, double,     \
                                           FaceField<D>&);                                                          \
  template double wall_normal_stress<D>(const MacGrid<D>&, const CellState<D>&, const std::vector<double>&,        \
                                        const FaceField<D>&, double, int, int, const Index<D>&);                    \
  template void wall_friction<D>(const MacGrid<D>&, const CellState<D>&, const SandCells<D>&,                       \
                                 const std::vector<double>&, const FaceField<D>&, const SideFriction<D>&, double,   \
                                 FaceField<D>&);                                                                    \
  template std::vector<std::vector<std::size_t>> rigid_groups<D>(const MacGrid<D>&, const std::vector<std::uint8_t>&); \
  template std::vector<GroupFace> group_faces<D>(const MacGrid<D>&, const CellState<D>&,                           \
                                                 const std::vector<std::size_t>&);                                 \
  template RigidFit<D> fit_rigid_motion<D>(const MacGrid<D>&, const std::vector<GroupFace>&, const Vec<D>&,         \
                                           const FaceField<D>&);                                                    \
  template void group_wall_friction<D>(const MacGrid<D>&, const std::vector<std::size_t>&,                          \
                                       const std::vector<GroupFace>&, const RigidFit<D>&, const SideFriction<D>&,  \
                                       RigidFit<D>&);                                                              \
  template void apply_rigid_motion<D>(const MacGrid<D>&, const std::vector<GroupFace>&, const RigidFit<D>&,         \
                                      FaceField<D>&);
SC_FLIP_SAND(2)
SC_FLIP_SAND(3)
#undef SC_FLIP_SAND

}  // namespace sc::flip
