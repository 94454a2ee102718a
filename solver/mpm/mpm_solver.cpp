#include "mpm/mpm_solver.hpp"

#include <algorithm>
#include <cmath>

#include "mpm/bspline.hpp"
#include "mpm/exchange.hpp"
#include "mpm/grid_field.hpp"
#include "mpm/svd.hpp"

namespace sc::mpm {

namespace {
/// Loops shorter than this run on one thread: a parallel region costs more than they do. The
/// result is the same either way (every node and particle is computed by one thread alone).
constexpr long parallel_min = 4096;
}  // namespace

template <int D>
void Nodes<D>::resize(std::size_t n) {
  for (auto* f : {&m_s, &m_w, &V_s, &V_w, &saturation, &pressure}) f->assign(n, 0.0);
  porosity.assign(n, 1.0);
  v_s.assign(n, Vec<D>::Zero());
  v_w.assign(n, Vec<D>::Zero());
}

template <int D>
MpmSolver<D>::MpmSolver(Params<D> params, Particles<D> particles) : params_(std::move(params)), ps_(std::move(particles)) {
  for (std::size_t i = 0; i < ps_.size(); ++i) (ps_.is_sand(i) ? sand_ : water_).push_back(i);
  mixture_ = !sand_.empty() && !water_.empty();
  loaded_ = std::any_of(ps_.load.begin(), ps_.load.end(), [](const Vec<D>& f) { return !f.isZero(0.0); });
  nodes_.resize(params_.grid.node_count());
  affine_.resize(ps_.size());
  weights_.resize(ps_.size());
  tau_.assign(ps_.size(), Mat<D>::Zero());
  for (const std::size_t i : sand_) tau_[i] = hencky_kirchhoff<D>(ps_.Fe[i], params_.sand);
  clamped_.resize(params_.grid.node_count());
  for (std::size_t k = 0; k < clamped_.size(); ++k) clamped_[k] = clamped(params_.grid.position(params_.grid.axes(k)));
  free_sand_ = std::any_of(sand_.begin(), sand_.end(), [&](std::size_t i) { return !clamped(ps_.x[i]); });
}

template <int D>
bool MpmSolver<D>::clamped(const Vec<D>& x) const {
  const double eps = 1e-9 * params_.grid.h;
  for (const auto& [lo, hi] : params_.clamps)
    if (((x.array() >= lo.array() - eps) && (x.array() <= hi.array() + eps)).all()) return true;
  return false;
}

template <int D>
double MpmSolver<D>::stable_step() const {
  double c = 0.0, v = 0.0;
  const double c_s2 = (params_.sand.lambda + 2.0 * params_.sand.mu) / params_.sand_density;
  const double c_w = params_.eos.sound_speed;
  if (!sand_.empty()) c = std::sqrt(c_s2);
  if (!water_.empty()) c = std::max(c, c_w);
  if (mixture_ && free_sand_) c = std::sqrt(c_s2 + mixture_wave_factor(params_.porosity, params_.water_density, params_.sand_density) * c_w * c_w);
  for (const Vec<D>& u : ps_.v) v = std::max(v, u.norm());
  return params_.cfl * params_.grid.h / (c + v);
}

template <int D>
int MpmSolver<D>::advance(double dt, double stable) {
  const int n = std::max(1, static_cast<int>(std::ceil(dt / stable - 1e-9)));
  for (int s = 0; s < n; ++s) substep(dt / n);
  return n;
}

template <int D>
void MpmSolver<D>::substep(double dt) {
  {
    auto scope = timers_.time(MpmStage::Stress);
    affine_momenta(dt);
  }
  {
    auto scope = timers_.time(MpmStage::Transfer);
    gather(dt);
  }

  update_grid(dt);
  {
    auto scope = timers_.time(MpmStage::Transfer);
    scatter(dt);
  }
  auto scope = timers_.time(MpmStage::Stress);
  const long n = static_cast<long>(sand_.size());
#pragma omp parallel for schedule(static) if (n >= parallel_min)
  for (long k = 0; k < n; ++k) plasticity(sand_[k]);
  time_ += dt;
}

template <int D>
double MpmSolver<D>::cohesion(std::size_t i) const {
  return params_.wet_cohesion_loss ? wet_cohesion(params_.cohesion, ps_.saturation[i]) : params_.cohesion;
}

template <int D>
Mat<D> MpmSolver<D>::kirchhoff(std::size_t i) const {
  return ps_.is_sand(i) ? tau_[i] : water_kirchhoff<D>(ps_.J[i], params_.water_density, params_.eos);
}

/// The APIC momentum matrix with the MLS-MPM stress impulse folded in, m_p C_p − Δt V_p⁰ D_p⁻¹ τ_p, so
/// that a node's momentum is Σ_p w_ip (m_p v_p + A_p (x_i − x_p)). In a mixture the water keeps its
/// pressure for the nodes instead (gather shares its force between the phases).
/// [Jiang 2015: APIC transfer] [Hu 2018: MLS-MPM force]
template <int D>
void MpmSolver<D>::affine_momenta(double dt) {
  const double Dinv = inertia_inverse(params_.grid.h);
#pragma omp parallel for schedule(static) if (static_cast<long>(ps_.size()) >= parallel_min)
  for (std::size_t i = 0; i < ps_.size(); ++i) {
    const Mat<D> tau = kirchhoff(i);
    if (mixture_ && !ps_.is_sand(i)) {
      ps_.pressure[i] = -tau(0, 0) / ps_.J[i];
      affine_[i] = ps_.m[i] * ps_.C[i];
    } else {
      affine_[i] = ps_.m[i] * ps_.C[i] - dt * ps_.V0[i] * Dinv * tau;
    }
  }
}

/// Particle-to-grid, gathered per node: mass Σ w m, momentum Σ w (m v + A (x_i − x_p)) and volume
/// Σ w V0 of each phase, then the velocity momentum/mass. [Jiang 2015: APIC P2G] The particles'
/// loads add their impulse Σ w Δt f_p, the nodal external force of the particle's share of a surface
/// traction. [Sulsky 1994: external forces on the grid] In a mixture also
/// the water's pressure Σ w m p / Σ w m and mixture volume Σ w J V0 / n, the sand's Σ w J V0, the
/// node's porosity n_i (node_porosity),
/// and the pore pressure's impulse on the mixture, Δt Σ_water w J p (V0/n) D⁻¹ (x_i − x_p) (the MLS
/// force of −p over the mixture volume the water fills, ≈ −Δt ∇p V), of which the water takes n_i and
/// the sand 1 − n_i. [Hu 2018: MLS-MPM force] [Zienkiewicz & Shiomi 1984: u-U equations]
template <int D>
void MpmSolver<D>::gather(double dt) {
  const Grid<D>& grid = params_.grid;
  bin_particles<D>(grid, ps_.x, sand_, sand_bins_);
  bin_particles<D>(grid, ps_.x, water_, water_bins_);
  const long count = static_cast<long>(ps_.size());
#pragma omp parallel for schedule(static) if (count >= parallel_min)
  for (long q = 0; q < count; ++q) weights_[q] = axis_weights<D>(grid, ps_.x[q]);
  // `pore` (a mixture's water only): Σ w m p, Σ w J V0 / n and the pore pressure's force
  struct PoreSums {
    double mass_pressure = 0.0, mixture_volume = 0.0;
    Vec<D> force = Vec<D>::Zero();
  };
  const double Dinv = inertia_inverse(grid.h);
  const auto one_phase = [&](const Bins& bins, const std::array<long, D>& node, double& m, double& V, Vec<D>& v,
                             double* V_now, PoreSums* pore) {
    const Vec<D> xi = grid.position(node);
    Vec<D> p = Vec<D>::Zero();
    m = V = 0.0;
    for_particles_near<D>(grid, bins, node, [&](std::size_t q, const std::array<int, D>& offset) {
      const Vec<D> r = xi - ps_.x[q];
      const double w = weight<D>(weights_[q], offset);
      m += w * ps_.m[q];
      V += w * ps_.V0[q];
      if (V_now) *V_now += w * ps_.J[q] * ps_.V0[q];
      p += w * (ps_.m[q] * ps_.v[q] + affine_[q] * r);
      if (loaded_) p += w * dt * ps_.load[q];
      if (!pore) return;
      const double mixture = ps_.J[q] * ps_.V0[q] / ps_.porosity[q];
      pore->mass_pressure += w * ps_.m[q] * ps_.pressure[q];
      pore->mixture_volume += w * mixture;
      pore->force += w * mixture * ps_.pressure[q] * Dinv * r;
    });
    v = m > 0.0 ? Vec<D>(p / m) : Vec<D>::Zero();
  };
  const long n = static_cast<long>(grid.node_count());
#pragma omp parallel for schedule(static) if (n >= parallel_min)
  for (long k = 0; k < n; ++k) {
    const std::array<long, D> node = grid.axes(static_cast<std::size_t>(k));
    PoreSums pore;
    double sand_now = 0.0;  // Σ w J V0 of the sand
    one_phase(sand_bins_, node, nodes_.m_s[k], nodes_.V_s[k], nodes_.v_s[k], &sand_now, nullptr);
    one_phase(water_bins_, node, nodes_.m_w[k], nodes_.V_w[k], nodes_.v_w[k], nullptr, mixture_ ? &pore : nullptr);
    nodes_.saturation[k] = node_saturation(nodes_.V_s[k], nodes_.V_w[k], params_.porosity);
    if (!mixture_) continue;
    const double n_i = node_porosity(nodes_.V_s[k], sand_now, pore.mixture_volume, params_.porosity);
    nodes_.porosity[k] = n_i;
    if (nodes_.m_w[k] <= 0.0) {
      nodes_.pressure[k] = 0.0;
      continue;
    }
    nodes_.pressure[k] = pore.mass_pressure / nodes_.m_w[k];
    nodes_.v_w[k] += dt * n_i * pore.force / nodes_.m_w[k];
    if (nodes_.m_s[k] > 0.0) nodes_.v_s[k] += dt * (1.0 - n_i) * pore.force / nodes_.m_s[k];
  }
}

/// Gravity, the exchange where both phases have mass, the start-up damping, the clamps, then each
/// phase's walls.
template <int D>
void MpmSolver<D>::update_grid(double dt) {
  {
    auto scope = timers_.time(MpmStage::Grid);
    for (std::size_t k = 0; k < nodes_.m_s.size(); ++k) {
      if (nodes_.m_s[k] > 0.0) nodes_.v_s[k] += dt * params_.gravity;
      if (nodes_.m_w[k] > 0.0) nodes_.v_w[k] += dt * params_.gravity;
    }
  }
  {
    auto scope = timers_.time(MpmStage::Exchange);
    exchange(dt);
  }
  auto scope = timers_.time(MpmStage::Grid);
  const double damping = time_ < params_.relax_until ? std::exp(-params_.relax_rate * dt) : 1.0;
  const long n = static_cast<long>(nodes_.m_s.size());
#pragma omp parallel for schedule(static) if (n >= parallel_min)
  for (long k = 0; k < n; ++k) {
    const std::array<long, D> node = params_.grid.axes(static_cast<std::size_t>(k));
    nodes_.v_s[k] *= damping;
    nodes_.v_w[k] *= damping;
    if (clamped_[k]) nodes_.v_s[k].setZero();
    apply_walls(node, true, nodes_.v_s[k]);
    apply_walls(node, false, nodes_.v_w[k]);
  }
}

template <int D>
void MpmSolver<D>::exchange(double dt) {
  if (params_.drag <= 0.0) return;
  const long n = static_cast<long>(nodes_.m_s.size());
#pragma omp parallel for schedule(static) if (n >= parallel_min)
  for (long k = 0; k < n; ++k) {
    if (nodes_.m_s[k] <= 0.0 || nodes_.m_w[k] <= 0.0) continue;
    const double a =
        dt * node_drag(params_.drag, nodes_.V_s[k], nodes_.saturation[k], nodes_.porosity[k], params_.porosity);
    if (clamped_[k])
      exchange_with_clamped_sand<D>(nodes_.m_w[k], a, nodes_.v_w[k]);
    else
      exchange_momentum<D>(nodes_.m_s[k], nodes_.m_w[k], a, nodes_.v_s[k], nodes_.v_w[k]);
  }
}

/// The wall rule of a node on or beyond a side: the velocity into the wall is removed; sand on a
/// rough side keeps a tangential velocity reduced by μ times the removed normal one (stopping
/// when that is more), water and sand on smooth sides slip. A velocity leaving the wall is kept.
/// [Stomakhin 2013: Coulomb friction at colliding grid nodes]
template <int D>
void MpmSolver<D>::apply_walls(const std::array<long, D>& node, bool sand, Vec<D>& v) const {
  const Vec<D> x = params_.grid.position(node);
  const double eps = 1e-9 * params_.grid.h;
  for (int d = 0; d < D; ++d)
    for (const int side : {0, 1}) {
      const bool beyond = side == 0 ? x[d] <= params_.wall_lo[d] + eps : x[d] >= params_.wall_hi[d] - eps;
      const double inward = side == 0 ? 1.0 : -1.0;
      const double vn = inward * v[d];
      if (!beyond || vn >= 0.0) continue;
      v[d] = 0.0;
      if (!sand || !params_.rough[2 * d + side]) continue;
      const double vt = v.norm(), loss = params_.wall_friction * -vn;
      v = vt <= loss ? Vec<D>::Zero() : Vec<D>(v * (1.0 - loss / vt));
    }
}

/// Grid-to-particle: v_p = Σ w v_i, C_p = D⁻¹ Σ w v_i (x_i − x_p)ᵀ, the sand's saturation Σ w s_i,
/// x_p += Δt v_p (kept within the walls), J and the sand's trial F^E by (𝟙 + Δt C_p).
/// [Jiang 2015: APIC G2P] [Hu 2018: MLS-MPM deformation update] In a mixture the sand's pore
/// pressure Σ w p_i, and the porosity at the water particle n_p = 1 − Σ w (1 − n_i) (exactly 1 in
/// open water), whose change since the last transfer scales its J by n_new/n_old: the water keeps its
/// own volume where it enters pores (its mixture volume grows by 1/n there) and where it leaves
/// them; the first transfer only replaces the seeding porosity by the grid's, whose smoothing of a
/// bed's surface is no motion of the water. [Zienkiewicz & Shiomi 1984: volume fractions]
template <int D>
void MpmSolver<D>::scatter(double dt) {
  const Grid<D>& grid = params_.grid;
  const double Dinv = inertia_inverse(grid.h);
  const long n = static_cast<long>(ps_.size());
#pragma omp parallel for schedule(static) if (n >= parallel_min)
  for (long q = 0; q < n; ++q) {
    const bool sand = ps_.is_sand(q);
    const std::vector<Vec<D>>& vi = sand ? nodes_.v_s : nodes_.v_w;
    Vec<D> v = Vec<D>::Zero();
    Mat<D> B = Mat<D>::Zero();
    double s = 0.0, pressure = 0.0, solid = 0.0;
    for_stencil<D>(grid, ps_.x[q], weights_[q], [&](std::size_t k, const Vec<D>& r, double w) {
      v += w * vi[k];
      B += w * vi[k] * r.transpose();
      s += w * nodes_.saturation[k];
      if (!mixture_) return;
      pressure += w * nodes_.pressure[k];
      solid += w * (1.0 - nodes_.porosity[k]);
    });
    ps_.v[q] = v;
    ps_.C[q] = Dinv * B;
    ps_.x[q] = (ps_.x[q] + dt * v).cwiseMax(params_.wall_lo).cwiseMin(params_.wall_hi);
    const Mat<D> step = Mat<D>::Identity() + dt * ps_.C[q];
    ps_.J[q] *= step.determinant();
    if (mixture_ && !sand) {
      if (transferred_) ps_.J[q] *= (1.0 - solid) / ps_.porosity[q];
      ps_.porosity[q] = 1.0 - solid;
    }
    if (!sand) continue;
    if (mixture_) ps_.pressure[q] = pressure;
    ps_.saturation[q] = std::min(1.0, s);
    ps_.Fe[q] = step * ps_.Fe[q];
  }
  transferred_ = true;
}

/// The return mapping of sand particle i on the SVD F^E = U Σ Vᵀ: ε = log Σ projected
/// (project_drucker_prager), F^E = U exp(ε) Vᵀ, and the particle's stress τ = hencky_kirchhoff(U, ε)
/// from the same decomposition. [Klár 2016: plasticity in log-strain space]
template <int D>
void MpmSolver<D>::plasticity(std::size_t i) {
  const Svd<D> s = svd<D>(ps_.Fe[i]);
  const Projection<D> p = project_drucker_prager<D>(s.sigma.array().log().matrix(), cohesion(i), ps_.vc[i], params_.sand);
  ps_.vc[i] = p.volume_correction;
  ps_.Fe[i] = s.U * Vec<D>(p.eps.array().exp().matrix()).asDiagonal() * s.V.transpose();
  tau_[i] = hencky_kirchhoff<D>(s.U, p.eps, params_.sand);
}

template struct Nodes<2>;
template struct Nodes<3>;
template class MpmSolver<2>;
template class MpmSolver<3>;

}  // namespace sc::mpm
