#include "porous/rigid_pore_pressure.hpp"

#include <Eigen/SparseCore>

#include <algorithm>
#include <array>
#include <cstring>
#include <string>
#include <tuple>
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

namespace {

/// One water particle of a column: its column (cell of the horizontal axes), height, mass, and
/// its place in the one-process storage (index, or key when decomposed).
template <int D>
struct ColumnMember {
  std::array<long, D - 1> cell;
  double z, m;
  std::uint64_t at;
};

/// Heights of the water in column `cell` and in the columns beside it (3^(D-1) columns), from
/// the top: in a disordered pond one column of width s misses a particle now and then, so its own
/// heights show gaps that its neighbours fill.
template <int D, class Columns>
std::vector<double> heights_around(const Columns& columns, const std::array<long, D - 1>& cell) {
  std::vector<double> z;
  const int beside = D == 2 ? 3 : 9;
  for (int k = 0; k < beside; ++k) {
    std::array<long, D - 1> c = cell;
    for (int a = 0, rest = k; a < D - 1; ++a, rest /= 3) c[a] += rest % 3 - 1;
    const auto it = columns.find(c);
    if (it == columns.end()) continue;
    for (const auto& member : it->second) z.push_back(std::get<0>(member));
  }
  std::sort(z.begin(), z.end(), std::greater<>());
  return z;
}

/// Whether `around` (heights from the top, `upper` and `lower` among them) leaves an empty height
/// of more than `gap` between `upper` and `lower`: no water around a column's gap, so the water
/// above it does not rest on the water below (a porous bed between them).
bool empty_between(const std::vector<double>& around, double upper, double lower, double gap) {
  auto k = std::lower_bound(around.begin(), around.end(), upper, std::greater<>());
  const auto end = std::upper_bound(around.begin(), around.end(), lower, std::greater<>());
  for (; k != end && k + 1 != end; ++k)
    if (*k - *(k + 1) > gap) return true;
  return false;
}

/// Column pressures of `members` (every water particle of the scene), by member.
template <int D>
std::vector<std::pair<std::uint64_t, double>> column_pressures(const std::vector<ColumnMember<D>>& members, double spacing,
                                                               double full_mass, double fluid_density, double gravity) {
  std::map<std::array<long, D - 1>, std::vector<std::tuple<double, std::uint64_t, double>>> columns;
  for (const ColumnMember<D>& c : members) columns[c.cell].emplace_back(c.z, c.at, c.m);
  std::vector<std::pair<std::uint64_t, double>> P;
  P.reserve(members.size());
  const double per_mass = fluid_density * gravity * spacing / full_mass;
  for (auto& [cell, column] : columns) {
    std::sort(column.begin(), column.end(), std::greater<>());  // from the top; equal heights: later in storage first
    const std::vector<double> around = heights_around<D>(columns, cell);
    double above = 0.0, last = INFINITY;
    for (const auto& [z, at, m] : column) {
      if (last - z > kColumnGap * spacing && empty_between(around, last, z, kColumnGap * spacing))
        above = 0.0;  // a gap with no water beside it: the water above does not rest on this
      P.emplace_back(at, per_mass * (above + 0.5 * m));
      above += m;
      last = z;
    }
  }
  std::sort(P.begin(), P.end());
  return P;
}

}  // namespace

template <int D>
std::vector<double> water_column_pressure(const ParticleSet<D>& ps, double spacing, double full_mass,
                                          double fluid_density, double gravity, const Decomposition<D>* ranks) {
  const auto at = [&](std::size_t i) { return ranks ? ranks->key(i) : static_cast<std::uint64_t>(i); };
  std::vector<ColumnMember<D>> members;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps.phase_of(i) != Phase::Water || (ranks && ranks->is_halo(i))) continue;
    ColumnMember<D> c;
    for (int a = 0; a < D - 1; ++a) c.cell[a] = std::lround(std::floor(ps.x[i][a] / spacing));
    c.z = ps.x[i][D - 1];
    c.m = ps.m[i];
    c.at = at(i);
    members.push_back(c);
  }
  if (ranks) members = ranks->all_gather_plain(members);
  const std::vector<std::pair<std::uint64_t, double>> column = column_pressures(members, spacing, full_mass, fluid_density, gravity);
  std::vector<double> P(ps.size(), 0.0);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (ps.phase_of(i) != Phase::Water) continue;
    const auto it = std::lower_bound(column.begin(), column.end(), std::pair<std::uint64_t, double>(at(i), -INFINITY));
    P[i] = it->second;
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

namespace {

/// Row of the pore-pressure system for the unknown at storage place `at` (index, or key when
/// decomposed): warm start, right-hand side, diagonal, and the off-diagonal entries (the unknown
/// neighbour's place, weight) in neighbour-list order.
struct PressureRow {
  std::uint64_t at = 0;
  double guess = 0, rhs = 0, diagonal = 0;
  std::vector<std::pair<std::uint64_t, double>> off;
};

/// PressureRows as bytes and back (decomposed runs gather them).
std::string encode_rows(const std::vector<PressureRow>& rows) {
  std::string out;
  const auto put = [&](const auto& v) { out.append(reinterpret_cast<const char*>(&v), sizeof v); };
  for (const PressureRow& r : rows) {
    put(r.at);
    put(r.guess);
    put(r.rhs);
    put(r.diagonal);
    put(static_cast<std::uint64_t>(r.off.size()));
    for (const auto& [place, weight] : r.off) {
      put(place);
      put(weight);
    }
  }
  return out;
}

void decode_rows(const std::string& in, std::vector<PressureRow>& rows) {
  std::size_t at = 0;
  const auto take = [&](auto& v) {
    std::memcpy(&v, in.data() + at, sizeof v);
    at += sizeof v;
  };
  while (at < in.size()) {
    PressureRow& r = rows.emplace_back();
    std::uint64_t n = 0;
    take(r.at);
    take(r.guess);
    take(r.rhs);
    take(r.diagonal);
    take(n);
    r.off.resize(n);
    for (auto& [place, weight] : r.off) {
      take(place);
      take(weight);
    }
  }
}

}  // namespace

template <int D>
void solve_harmonic_pressure(const ParticleSet<D>& ps, const NeighbourGrid<D>& nb,
                             const std::vector<PressureRole>& role, const std::vector<double>& suction,
                             double fluid_density, const Vec<D>& gravity, std::vector<double>& P,
                             const Decomposition<D>* ranks) {
  // Φ = P − head, head = ρ^f g·x + P^c: the piezometric pore-water pressure
  auto head = [&](std::size_t i) { return fluid_density * gravity.dot(ps.x[i]) + suction[i]; };
  const auto place = [&](std::size_t i) { return ranks ? ranks->key(i) : static_cast<std::uint64_t>(i); };
  std::vector<PressureRow> rows;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (role[i] != PressureRole::Unknown || (ranks && ranks->is_halo(i))) continue;
    PressureRow& row = rows.emplace_back();
    row.at = place(i);
    row.guess = P[i] - head(i);
    for (const auto j : nb.of(i)) {
      if (j == i || role[j] == PressureRole::None) continue;
      const Vec<D> d = ps.x[i] - ps.x[j];
      const double r = d.norm();
      const double w = kernel::spiky_gradient<D>(d, r, 0.5 * (ps.h[i] + ps.h[j])).norm() / r;
      row.diagonal += w;
      if (role[j] == PressureRole::Unknown)
        row.off.emplace_back(place(j), -w);
      else
        row.rhs += w * (P[j] - head(j));
    }
  }
  if (ranks) {  // every rank's rows, in the one-process order (each rank's are in key order)
    const std::vector<std::string> all = ranks->comm().all_gather(encode_rows(rows));
    rows.clear();
    for (const std::string& bytes : all) decode_rows(bytes, rows);
    std::sort(rows.begin(), rows.end(), [](const PressureRow& a, const PressureRow& b) { return a.at < b.at; });
  }
  const auto unknowns = static_cast<long>(rows.size());
  if (unknowns == 0) return;
  std::vector<std::uint64_t> order(rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k) order[k] = rows[k].at;
  const auto index = [&](std::uint64_t at) { return static_cast<long>(std::lower_bound(order.begin(), order.end(), at) - order.begin()); };
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::VectorXd rhs(unknowns), guess(unknowns);
  for (long k = 0; k < unknowns; ++k) {
    const PressureRow& row = rows[k];
    guess[k] = row.guess;
    rhs[k] = row.rhs;
    for (const auto& [at, w] : row.off) entries.emplace_back(k, index(at), w);
    entries.emplace_back(k, k, row.diagonal * (1.0 + kRegularisation) + (row.diagonal > 0.0 ? 0.0 : 1.0));
  }
  Eigen::SparseMatrix<double> A(unknowns, unknowns);
  A.setFromTriplets(entries.begin(), entries.end());
  Eigen::VectorXd x = guess;
  conjugate_gradient(A, rhs, x, kTolerance);
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (role[i] == PressureRole::Unknown) P[i] = x[index(place(i))] + head(i);
}

template std::vector<double> water_column_pressure<2>(const ParticleSet<2>&, double, double, double, double, const Decomposition<2>*);
template std::vector<double> water_column_pressure<3>(const ParticleSet<3>&, double, double, double, double, const Decomposition<3>*);
template double pond_pressure<2>(const ParticleSet<2>&, const NeighbourGrid<2>&, const std::vector<double>&, std::size_t,
                                 double, const Vec<2>&);
template double pond_pressure<3>(const ParticleSet<3>&, const NeighbourGrid<3>&, const std::vector<double>&, std::size_t,
                                 double, const Vec<3>&);
template void solve_harmonic_pressure<2>(const ParticleSet<2>&, const NeighbourGrid<2>&, const std::vector<PressureRole>&,
                                         const std::vector<double>&, double, const Vec<2>&, std::vector<double>&, const Decomposition<2>*);
template void solve_harmonic_pressure<3>(const ParticleSet<3>&, const NeighbourGrid<3>&, const std::vector<PressureRole>&,
                                         const std::vector<double>&, double, const Vec<3>&, std::vector<double>&, const Decomposition<3>*);

}  // namespace sc
