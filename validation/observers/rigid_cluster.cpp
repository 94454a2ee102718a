// Observer "rigid_cluster": rigid clusters against exact rigid-body mechanics (REFERENCES.md §6).
// While the case runs, a cohesive sand block (the first block, one cluster) falls freely: its centre
// of mass must follow x0 + g t²/2 and it must stay one cluster. At the end, the rigid-body code of
// solver/sand/rigid_body.hpp is exercised directly on 3-D point lattices:
//   inertia_identity_error       n³ lattice: |I_xx − M a²(1 − 1/n²)/6| / I_xx (eq 17);
//   linear_acceleration_error    off-centre force from rest, one projection (eqs 13-18): |a − F/M|/|F/M|;
//   angular_acceleration_error   the same force: |α − I⁻¹(r × F)| / |α| (eqs 12b, 14-16);
//   couple_force_residual        a pure couple: |a| M / |f| (must vanish) with α as predicted;
//   energy_drift_max, angular_momentum_drift_max
//                                torque-free spin about each principal axis for 100 periods (midpoint
//                                rotation with ω = I(t)⁻¹ L: the gyroscopic term is kept);
//   stable_axis_wobble_max       largest |ω⊥|/Ω about the minor and major axes (stable: stays small);
//   intermediate_axis_flip       smallest ω₂/Ω about the intermediate axis (−1: it flipped);
//   growth_rate_ratio            fitted growth rate of ω⊥ about axis 2 / Ω √((I2−I1)(I3−I2)/(I1 I3));
//   explicit_euler_energy_gain   negative control: explicit Euler on Euler's equations, same step, gains
//                                energy (must exceed the 1e-3 gate);
//   free_fall_error              max |y_cm − y_exact| / (g T²/2) of the simulated block;
//   cluster_count_max            most clusters of the simulated block in a step (1: it stayed rigid).
#include <cmath>

#include "observer.hpp"
#include "observers/sand_deposit.hpp"
#include "sand/rigid_body.hpp"
#include "simulator/sph_probe.hpp"

namespace sc {

namespace {

using Cloud = VecArrayOf<3>;

/// A centred nx × ny × nz lattice of unit point masses at spacing s.
Cloud box_lattice(int nx, int ny, int nz, double s) {
  Cloud out;
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j)
      for (int k = 0; k < nz; ++k)
        out.push_back(Vec<3>((i - 0.5 * (nx - 1)) * s, (j - 0.5 * (ny - 1)) * s, (k - 0.5 * (nz - 1)) * s));
  return out;
}

std::vector<std::size_t> indices(std::size_t n) {
  std::vector<std::size_t> out(n);
  for (std::size_t k = 0; k < n; ++k) out[k] = k;
  return out;
}

struct SpinResult {
  double energy_drift = 0.0, momentum_drift = 0.0, wobble = 0.0, min_axial = 1.0;
  std::vector<double> t, log_perp, energy;
};

/// Torque-free spin of `body` (principal axes = coordinate axes) started at Ω e_axis plus a small
/// perturbation, for `periods` periods of 2π/Ω at `steps` steps per period. Each step: ω0 = I(R)⁻¹L,
/// half rotation, ω½ = I(R½)⁻¹L, full rotation by ω½ Δt (explicit midpoint on the rotation group).
SpinResult spin(const Cloud& body, const std::vector<double>& m, int axis, double Omega, int periods, int steps) {
  const auto members = indices(body.size());
  const Mat<3> I_body = inertia_tensor<3>(members, m, body, Vec<3>::Zero());
  Vec<3> w0 = Vec<3>::Constant(1e-6 * Omega);
  w0[axis] = Omega;
  const Vec<3> L = I_body * w0;
  const double E0 = 0.5 * w0.dot(L), dt = 2.0 * pi / Omega / steps;
  auto omega_at = [&](const Mat<3>& R) {
    Cloud x(body.size());
    for (std::size_t k = 0; k < body.size(); ++k) x[k] = R * body[k];
    return solve_inertia<3>(inertia_tensor<3>(members, m, x, Vec<3>::Zero()), L);
  };
  SpinResult r;
  Mat<3> R = Mat<3>::Identity();
  for (long n = 0; n <= static_cast<long>(periods) * steps; ++n) {
    const Vec<3> w = omega_at(R);
    const Vec<3> w_body = R.transpose() * w;
    const Vec<3> Lw = R * I_body * w_body;  // L recomputed from the motion: Σ m r × (ω × r)
    const double E = 0.5 * w.dot(Lw);
    r.energy_drift = std::max(r.energy_drift, std::abs(E / E0 - 1.0));
    r.momentum_drift = std::max(r.momentum_drift, std::abs(Lw.norm() / L.norm() - 1.0));
    Vec<3> perp = w_body;
    perp[axis] = 0.0;
    r.wobble = std::max(r.wobble, perp.norm() / Omega);
    r.min_axial = std::min(r.min_axial, w_body[axis] / Omega);
    if (n % (steps / 20) == 0) {
      r.t.push_back(n * dt * Omega / (2.0 * pi));
      r.log_perp.push_back(std::log(perp.norm() / Omega));
      r.energy.push_back(E / E0 - 1.0);
    }
    const Mat<3> R_half = rotation<3>(0.5 * dt * w) * R;
    R = rotation<3>(dt * omega_at(R_half)) * R;
  }
  return r;
}

/// Negative control: explicit Euler on Euler's equations I ω̇ = −ω × Iω in the body frame.
double explicit_euler_energy_gain(const Mat<3>& I, Vec<3> w, double dt, long steps) {
  const double E0 = 0.5 * w.dot(I * w);
  double worst = 0.0;
  for (long n = 0; n < steps; ++n) {
    w += dt * I.inverse() * (-w.cross(I * w));
    worst = std::max(worst, 0.5 * w.dot(I * w) / E0 - 1.0);
  }
  return worst;
}

template <int D>
class RigidClusterObserver : public Observer<D> {
 public:
  explicit RigidClusterObserver(const ObserverContext& ctx) {
    JsonObject o = validation_block(ctx);
    if (ctx.spec.blocks.empty() || ctx.spec.blocks.front().fill != BlockFill::Sand)
      o.fail("observer", "the rigid_cluster observer needs a sand block first");
    require_sph(ctx.spec, "the rigid_cluster observer (it counts SPH's rigid clusters)");
    periods_ = static_cast<int>(o.integer("periods", 1, 10000, 100));
    steps_ = static_cast<int>(o.integer("steps_per_period", 20, 100000, 400));
    limits_ = read_metric_limits(o);
    o.finish();
    g_ = ctx.spec.gravity[D - 1];
  }

  void sample(const Method<D>& run) override {
    const ParticleView<D> ps = run.particles();
    const std::vector<std::int32_t>& cluster = require_sph(run, "rigid_cluster").particles().cluster;
    double M = 0.0, y = 0.0;
    int clusters = 0;
    for (std::size_t i = 0; i < ps.size(); ++i) {
      if (ps.phase_of(i) != Phase::Sand) continue;
      M += ps.m[i];
      y += ps.m[i] * ps.x[i][D - 1];
      clusters = std::max(clusters, static_cast<int>(cluster[i]));
    }
    if (t_.empty()) y0_ = y / M;
    cluster_count_max_ = std::max(cluster_count_max_, clusters);
    t_.push_back(run.time());
    y_.push_back(y / M - y0_);
    y_exact_.push_back(0.5 * g_ * run.time() * run.time());
  }

  ObserverResult finish(const Method<D>&) override {
    ObserverResult r;
    lattice_identity(r);
    forced_body(r);
    spins(r);
    double worst = 0.0;
    for (std::size_t k = 0; k < t_.size(); ++k) worst = std::max(worst, std::abs(y_[k] - y_exact_[k]));
    add_metric(r, limits_, "free_fall_error", worst / std::abs(y_exact_.back()));
    add_metric(r, limits_, "cluster_count_max", cluster_count_max_);
    r.series.push_back({"fall_sim", "t [s]", "y_cm - y_cm(0) [m]", t_, y_});
    r.series.push_back({"fall_exact", "t [s]", "y_cm - y_cm(0) [m]", t_, y_exact_});
    r.plots.push_back({"free_fall.png", "Cohesive sand block (one rigid cluster) in free fall", "t [s]",
                       "y_cm - y_cm(0) [m]", {{"fall_sim", "SPH rigid cluster", "line"}, {"fall_exact", "g t^2/2", "line"}}});
    return r;
  }

 private:
  void lattice_identity(ObserverResult& r) {
    const int n = 10;
    const Cloud x = box_lattice(n, n, n, 0.1);
    const std::vector<double> m(x.size(), 0.7);
    const Mat<3> I = inertia_tensor<3>(indices(x.size()), m, x, Vec<3>::Zero());
    const double M = 0.7 * x.size(), a = n * 0.1;
    add_metric(r, limits_, "inertia_identity_error", std::abs(I(0, 0) / (M * a * a * (1.0 - 1.0 / (n * n)) / 6.0) - 1.0));
  }

  void forced_body(ObserverResult& r) {
    const Cloud x = box_lattice(6, 4, 3, 0.05);
    const std::vector<double> m(x.size(), 0.2);
    const auto members = indices(x.size());
    const Cloud rest(x.size(), Vec<3>::Zero());
    const double dt = 1e-3;
    Cloud f(x.size(), Vec<3>::Zero());
    f[5] = Vec<3>(0.3, -1.1, 0.7);
    ClusterMotion<3> c = rigid_motion<3>(members, m, x, rest, f, dt);
    const Vec<3> a_exact = f[5] / c.mass;
    const Vec<3> alpha_exact = c.inertia.inverse() * (x[5] - c.centre).cross(f[5]);
    add_metric(r, limits_, "linear_acceleration_error", (c.velocity / dt - a_exact).norm() / a_exact.norm());
    add_metric(r, limits_, "angular_acceleration_error", (c.omega / dt - alpha_exact).norm() / alpha_exact.norm());
    f[20] = -f[5];
    c = rigid_motion<3>(members, m, x, rest, f, dt);
    const Vec<3> couple = (x[5] - c.centre).cross(f[5]) + (x[20] - c.centre).cross(f[20]);
    add_metric(r, limits_, "couple_force_residual", (c.velocity / dt).norm() * c.mass / f[5].norm());
    add_metric(r, limits_, "couple_angular_acceleration_error",
               (c.omega / dt - c.inertia.inverse() * couple).norm() / (c.inertia.inverse() * couple).norm());
  }

  void spins(ObserverResult& r) {
    const Cloud body = box_lattice(6, 4, 2, 1.0);  // I1 < I2 < I3 about x, y, z
    const std::vector<double> m(body.size(), 1.0);
    const Mat<3> I = inertia_tensor<3>(indices(body.size()), m, body, Vec<3>::Zero());
    const double Omega = 2.0 * pi;
    double e = 0.0, l = 0.0, wobble = 0.0;
    SpinResult middle;
    for (int axis : {0, 2, 1}) {
      SpinResult s = spin(body, m, axis, Omega, periods_, steps_);
      e = std::max(e, s.energy_drift);
      l = std::max(l, s.momentum_drift);
      if (axis != 1) wobble = std::max(wobble, s.wobble);
      r.series.push_back({"energy_axis" + std::to_string(axis + 1) + "_sim", "t / period", "E/E0 - 1", s.t, s.energy});
      if (axis == 1) middle = s;
    }
    add_metric(r, limits_, "energy_drift_max", e);
    add_metric(r, limits_, "angular_momentum_drift_max", l);
    add_metric(r, limits_, "stable_axis_wobble_max", wobble);
    add_metric(r, limits_, "intermediate_axis_flip", middle.min_axial);
    const double I1 = I(0, 0), I2 = I(1, 1), I3 = I(2, 2);
    const double lambda = Omega * std::sqrt((I2 - I1) * (I3 - I2) / (I1 * I3));
    std::vector<double> ft, fy;
    for (std::size_t k = 0; k < middle.t.size(); ++k) {  // the first linear phase: 1e-5 < |ω⊥|/Ω < 1e-2
      if (middle.log_perp[k] >= std::log(1e-2)) break;
      if (middle.log_perp[k] <= std::log(1e-5)) continue;
      ft.push_back(middle.t[k] * 2.0 * pi / Omega);
      fy.push_back(middle.log_perp[k]);
    }
    add_metric(r, limits_, "growth_rate_ratio", ft.size() > 2 ? fitted_slope(ft, fy) / lambda : NAN);
    const Vec<3> w0(1e-6 * Omega, Omega, 1e-6 * Omega);
    add_metric(r, limits_, "explicit_euler_energy_gain",
               explicit_euler_energy_gain(I, w0, 2.0 * pi / Omega / steps_, static_cast<long>(periods_) * steps_));
    std::vector<double> exact;
    const double t0 = ft.empty() ? 0.0 : ft.front(), y0 = fy.empty() ? 0.0 : fy.front();
    for (double t : middle.t) exact.push_back(y0 + lambda * (t * 2.0 * pi / Omega - t0));
    r.series.push_back({"perp_axis2_sim", "t / period", "ln(|omega_perp| / Omega)", middle.t, middle.log_perp});
    r.series.push_back({"perp_axis2_exact", "t / period", "ln(|omega_perp| / Omega)", middle.t, exact});
    r.plots.push_back({"intermediate_axis.png", "Torque-free spin about the intermediate axis: growth of the wobble",
                       "t / period", "ln(|omega_perp| / Omega)",
                       {{"perp_axis2_sim", "rigid-body code", "line"},
                        {"perp_axis2_exact", "exact rate Omega sqrt((I2-I1)(I3-I2)/(I1 I3))", "line"}}});
    r.plots.push_back({"energy_drift.png", "Energy drift of torque-free spins (100 periods)", "t / period", "E/E0 - 1",
                       {{"energy_axis1_sim", "axis 1 (minor)", "line"}, {"energy_axis2_sim", "axis 2 (intermediate)", "line"},
                        {"energy_axis3_sim", "axis 3 (major)", "line"}}});
  }

  int periods_, steps_;
  double g_, y0_ = 0.0;
  int cluster_count_max_ = 0;
  std::vector<double> t_, y_, y_exact_;
  std::map<std::string, MetricLimit> limits_;
};

}  // namespace

template <int D>
std::unique_ptr<Observer<D>> make_rigid_cluster_observer(const ObserverContext& ctx) {
  return std::make_unique<RigidClusterObserver<D>>(ctx);
}
template std::unique_ptr<Observer<2>> make_rigid_cluster_observer<2>(const ObserverContext&);
template std::unique_ptr<Observer<3>> make_rigid_cluster_observer<3>(const ObserverContext&);

}  // namespace sc
