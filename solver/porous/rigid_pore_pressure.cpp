#include "porous/rigid_pore_pressure.hpp"

#include <Eigen/SparseCore>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>

#include "core/conjugate_gradient.hpp"
#include "sph/kernels.hpp"

namespace sc {

namespace {

constexpr double kRegularisation = 1e-9;
constexpr double kTolerance = 1e-10;
constexpr double kColumnGap = 1.5;  // spacings of empty height that end a water column

}  // namespace

template <int D>
std::vector<double> water_column_pressure(const ParticleSet<D>& ps, double spacing, double full_mass,
                                          double fluid_density, double gravity) {
  std::map<std::array<long, D - 1>, std::vector<std::pair<double, std::size_t>>> columns;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps.phase_of(i) != Phase::Water) continue;
    std::array<long, D - 1> cell;
    for (int a = 0; a < D - 1; ++a) cell[a] = std::lround(std::floor(ps.x[i][a] / spacing));
    columns[cell].emplace_back(ps.x[i][D - 1], i);
  }
  std::vector<double> P(ps.size(), 0.0);
  const double per_mass = fluid_density * gravity * spacing / full_mass;
  for (auto& [cell, members] : columns) {
    std::sort(members.begin(), members.end(), std::greater<>());
    double above = 0.0, last = INFINITY;
    for (const auto& [z, i] : members) {
      if (last - z > kColumnGap * spacing) above = 0.0;  // a gap: the water above does not rest on this
      P[i] = per_mass * (above + 0.5 * ps.m[i]);
      above += ps.m[i];
      last = z;
    }
  }
  return P;
}

template <int D>
double pond_pressure(const ParticleSet<D>& ps, const NeighbourGrid<D>& nb, const std::vector<double>& column,
                     std::size_t i, double fluid_density, const Vec<D>& gravity) {
  double sum_w = 0.0, sum_p = 0.0;
  for (const auto j : nb.of(i)) {
    if (ps.phase_of(j) != Phase::Water) continue;
    const Vec<D> d = ps.x[i] - ps.x[j];
    const double W = kernel::poly6<D>(d.norm(), ps.h[i]);
    sum_w += W;
    sum_p += W * (column[j] + fluid_density * gravity.dot(d));
  }
  return sum_w > 0.0 ? std::max(0.0, sum_p / sum_w) : 0.0;
}

template <int D>
void solve_harmonic_pressure(const ParticleSet<D>& ps, const NeighbourGrid<D>& nb,
                             const std::vector<PressureRole>& role, const std::vector<double>& suction,
                             double fluid_density, const Vec<D>& gravity, std::vector<double>& P) {
  // Φ = P − head, head = ρ^f g·x + P^c: the piezometric pore-water pressure
  auto head = [&](std::size_t i) { return fluid_density * gravity.dot(ps.x[i]) + suction[i]; };
  std::vector<long> index(ps.size(), -1);
  long unknowns = 0;
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (role[i] == PressureRole::Unknown) index[i] = unknowns++;
  if (unknowns == 0) return;
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(unknowns), guess(unknowns);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (index[i] < 0) continue;
    guess[index[i]] = P[i] - head(i);
    double diagonal = 0.0;
    for (const auto j : nb.of(i)) {
      if (j == i || role[j] == PressureRole::None) continue;
      const Vec<D> d = ps.x[i] - ps.x[j];
      const double r = d.norm();
      const double w = kernel::spiky_gradient<D>(d, r, 0.5 * (ps.h[i] + ps.h[j])).norm() / r;
      diagonal += w;
      if (index[j] >= 0)
        entries.emplace_back(index[i], index[j], -w);
      else
        rhs[index[i]] += w * (P[j] - head(j));
    }
    entries.emplace_back(index[i], index[i], diagonal * (1.0 + kRegularisation) + (diagonal > 0.0 ? 0.0 : 1.0));
  }
  Eigen::SparseMatrix<double> A(unknowns, unknowns);
  A.setFromTriplets(entries.begin(), entries.end());
  Eigen::VectorXd x = guess;
  conjugate_gradient(A, rhs, x, kTolerance);
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (index[i] >= 0) P[i] = x[index[i]] + head(i);
}

template std::vector<double> water_column_pressure<2>(const ParticleSet<2>&, double, double, double, double);
template std::vector<double> water_column_pressure<3>(const ParticleSet<3>&, double, double, double, double);
template double pond_pressure<2>(const ParticleSet<2>&, const NeighbourGrid<2>&, const std::vector<double>&, std::size_t,
                                 double, const Vec<2>&);
template double pond_pressure<3>(const ParticleSet<3>&, const NeighbourGrid<3>&, const std::vector<double>&, std::size_t,
                                 double, const Vec<3>&);
template void solve_harmonic_pressure<2>(const ParticleSet<2>&, const NeighbourGrid<2>&, const std::vector<PressureRole>&,
                                         const std::vector<double>&, double, const Vec<2>&, std::vector<double>&);
template void solve_harmonic_pressure<3>(const ParticleSet<3>&, const NeighbourGrid<3>&, const std::vector<PressureRole>&,
                                         const std::vector<double>&, double, const Vec<3>&, std::vector<double>&);

}  // namespace sc
