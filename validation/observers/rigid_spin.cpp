// Observer "rigid_spin": torque-free rigid clusters of the solver against Euler's equations
// (docs/references.md §6). The case holds three cohesive 3-D sand blocks, each with three different
// principal moments, far apart and without gravity, each spun (blocks[].angular_velocity) close to
// one of its principal axes: the smallest, the intermediate and the largest moment. Each body is
// followed through the view (its particles are the sand nearest its block's centre): L = Σ m r' × v
// about its centre of mass, I = Σ m (|r'|² 𝟙 − r' r'ᵀ), ω = I⁻¹L, and ω in the principal frame of I
// (axes kept right-handed and sign-continuous from sample to sample).
//   L_magnitude_drift       max over bodies and samples of ||L|/|L0| − 1| (L is conserved without torque);
//   L_direction_drift       max angle between L and L0 [rad];
//   spin_minor_angle, spin_major_angle   largest angle of ω from the principal axis of the smallest
//                           and largest moment that the body spins about [rad];
//   spin_minor_angle_ratio, spin_major_angle_ratio   those over the largest angle of the exact
//                           solution at the same times (analytic::torque_free_omega, GSL): the spin is
//                           stable and wobbles as Euler's equations say;
//   flip_count              sign changes of ω's intermediate component (Dzhanibekov flips);
//   flip_period_error       |T_sim/T − 1|, T_sim twice the mean interval between the flips, T the
//                           closed-form period of the torque-free body (analytic::torque_free_period);
//   cluster_count_max       most rigid clusters in a step (3: every body stayed one cluster);
//   loose_sand_max          most sand particles in no cluster in a step (0: all stayed rigid).
#include <array>

#include "observer.hpp"
#include "reference/analytic/free_rigid_body.hpp"
#include "scene/scene_builder.hpp"
#include "simulator/sph_probe.hpp"

namespace sc {

namespace {

constexpr std::array<const char*, 3> kAxisNames{"minor", "intermediate", "major"};

/// The principal moments (increasing) and axes (columns, right-handed) of an inertia tensor.
struct Principal {
  Vec<3> moments;
  Mat<3> axes;
};

Principal principal(const Mat<3>& I) {
  const Eigen::SelfAdjointEigenSolver<Mat<3>> es(I);
  Principal p{es.eigenvalues(), es.eigenvectors()};
  if (p.axes.determinant() < 0.0) p.axes.col(2) *= -1.0;
  return p;
}

/// The axis (0: smallest moment, 1: intermediate, 2: largest) that a block spins closest to, from
/// its lattice at spacing dx (equal masses); InputError if the block does not spin or two of its
/// moments are equal (no distinct principal axes).
int spin_axis(const CaseSpec& spec, std::size_t b, double dx) {
  const BlockSpec& block = spec.blocks[b];
  const std::string where = "/blocks/" + std::to_string(b);
  if (block.fill != BlockFill::Sand || block.angular_velocity.empty())
    throw InputError(spec.file, where, "the rigid_spin observer needs sand blocks with an angular_velocity");
  const auto points = lattice_points<3>(to_vec<3>(block.min), to_vec<3>(block.max), dx);
  Vec<3> centre = Vec<3>::Zero();
  for (const Vec<3>& x : points) centre += x / static_cast<double>(points.size());
  Mat<3> I = Mat<3>::Zero();
  for (const Vec<3>& x : points) I += (x - centre).squaredNorm() * Mat<3>::Identity() - (x - centre) * (x - centre).transpose();
  const Principal p = principal(I);
  if (!(p.moments[1] > (1.0 + 1e-6) * p.moments[0] && p.moments[2] > (1.0 + 1e-6) * p.moments[1]))
    throw InputError(spec.file, where, "the rigid_spin observer needs a block with three different edge lengths");
  const Vec<3> w = p.axes.transpose() * to_vec<3>(block.angular_velocity);
  int axis = 0;
  w.cwiseAbs().maxCoeff(&axis);
  return axis;
}

/// Angle between two vectors, accurate near 0 [rad].
double angle_between(const Vec<3>& a, const Vec<3>& b) { return std::atan2(a.cross(b).norm(), a.dot(b)); }

/// One spinning body as sampled: its block's centre, the axis it spins about and its history.
struct Body {
  Vec<3> home;
  int axis = 0;
  Vec<3> L0 = Vec<3>::Zero();
  Principal start, frame;          // at t = 0 and at the last sample
  std::vector<double> L_magnitude, L_direction;
  std::vector<analytic::Vec3> omega;  // ω in the principal frame
};

class RigidSpinObserver : public Observer<3> {
 public:
  explicit RigidSpinObserver(const ObserverContext& ctx) {
    JsonObject o = validation_block(ctx);
    require_sph(ctx.spec, "the rigid_spin observer (it counts SPH's rigid clusters)");
    limits_ = read_metric_limits(o);
    o.finish();
    std::array<bool, 3> taken{};
    for (std::size_t b = 0; b < ctx.spec.blocks.size(); ++b) {
      const int axis = spin_axis(ctx.spec, b, ctx.spacing);
      if (taken[axis])
        throw InputError(ctx.spec.file, "/blocks/" + std::to_string(b) + "/angular_velocity",
                         std::string("a second block spins about its ") + kAxisNames[axis] + " axis");
      taken[axis] = true;
      Body& body = bodies_.emplace_back();
      body.home = 0.5 * (to_vec<3>(ctx.spec.blocks[b].min) + to_vec<3>(ctx.spec.blocks[b].max));
      body.axis = axis;
    }
    if (bodies_.size() != 3)
      throw InputError(ctx.spec.file, "/blocks", "the rigid_spin observer needs three blocks, spun about the minor, intermediate and major axis");
  }

  void sample(const Method<3>& run) override {
    const ParticleView<3> ps = run.particles();
    const std::vector<std::size_t> owner = owners(ps);
    std::vector<double> mass(bodies_.size(), 0.0);
    std::vector<Vec<3>> centre(bodies_.size(), Vec<3>::Zero());
    for (std::size_t i = 0; i < ps.size(); ++i)
      if (owner[i] < bodies_.size()) {
        mass[owner[i]] += ps.m[i];
        centre[owner[i]] += ps.m[i] * ps.x[i];
      }
    std::vector<Vec<3>> L(bodies_.size(), Vec<3>::Zero());
    std::vector<Mat<3>> I(bodies_.size(), Mat<3>::Zero());
    for (std::size_t i = 0; i < ps.size(); ++i)
      if (owner[i] < bodies_.size()) {
        const Vec<3> r = ps.x[i] - centre[owner[i]] / mass[owner[i]];
        L[owner[i]] += ps.m[i] * r.cross(ps.v[i]);
        I[owner[i]] += ps.m[i] * (r.squaredNorm() * Mat<3>::Identity() - r * r.transpose());
      }
    for (std::size_t b = 0; b < bodies_.size(); ++b) record(bodies_[b], L[b], I[b]);
    t_.push_back(run.time());
    if (run.steps() > 0) count_clusters(run);
  }

  ObserverResult finish(const Method<3>&) override {
    ObserverResult r;
    double magnitude = 0.0, direction = 0.0;
    for (const Body& body : bodies_) {
      magnitude = std::max(magnitude, *std::max_element(body.L_magnitude.begin(), body.L_magnitude.end()));
      direction = std::max(direction, *std::max_element(body.L_direction.begin(), body.L_direction.end()));
    }
    add_metric(r, limits_, "L_magnitude_drift", magnitude);
    add_metric(r, limits_, "L_direction_drift", direction);
    for (const Body& body : bodies_) body.axis == 1 ? add_flip(r, body) : add_stable_spin(r, body);
    add_metric(r, limits_, "cluster_count_max", cluster_count_max_);
    add_metric(r, limits_, "loose_sand_max", loose_sand_max_);
    add_drift_series(r);
    return r;
  }

 private:
  /// The body of every particle: the nearest block centre for sand, bodies_.size() for the rest.
  std::vector<std::size_t> owners(const ParticleView<3>& ps) const {
    std::vector<std::size_t> owner(ps.size(), bodies_.size());
    for (std::size_t i = 0; i < ps.size(); ++i) {
      if (ps.phase_of(i) != Phase::Sand) continue;
      double nearest = INFINITY;
      for (std::size_t b = 0; b < bodies_.size(); ++b)
        if ((ps.x[i] - bodies_[b].home).norm() < nearest) {
          nearest = (ps.x[i] - bodies_[b].home).norm();
          owner[i] = b;
        }
    }
    return owner;
  }

  /// Appends a sample of the body of angular momentum L and inertia I.
  static void record(Body& body, const Vec<3>& L, const Mat<3>& I) {
    Principal now = principal(I);
    if (body.omega.empty()) {
      body.L0 = L;
      body.start = now;
    } else {
      for (int k = 0; k < 3; ++k)
        if (now.axes.col(k).dot(body.frame.axes.col(k)) < 0.0) now.axes.col(k) *= -1.0;
    }
    body.frame = now;
    const Vec<3> w = now.axes.transpose() * I.ldlt().solve(L);
    body.omega.push_back({w[0], w[1], w[2]});
    body.L_magnitude.push_back(std::abs(L.norm() / body.L0.norm() - 1.0));
    body.L_direction.push_back(angle_between(L, body.L0));
  }

  void count_clusters(const Method<3>& run) {
    const ParticleSet<3>& ps = require_sph(run, "rigid_spin").particles();
    int clusters = 0, loose = 0;
    for (std::size_t i = 0; i < ps.size(); ++i) {
      if (ps.phase_of(i) != Phase::Sand) continue;
      clusters = std::max(clusters, static_cast<int>(ps.cluster[i]));
      loose += ps.cluster[i] == 0 ? 1 : 0;
    }
    cluster_count_max_ = std::max(cluster_count_max_, clusters);
    loose_sand_max_ = std::max(loose_sand_max_, loose);
  }

  /// ω at the sample times by the exact solution from the body's state at t = 0.
  std::vector<analytic::Vec3> exact_omega(const Body& body) const {
    const analytic::Vec3 I{body.start.moments[0], body.start.moments[1], body.start.moments[2]};
    return analytic::torque_free_omega(I, body.omega.front(), t_);
  }

  /// The angle of each ω from principal axis k [rad].
  static std::vector<double> angles_from_axis(const std::vector<analytic::Vec3>& omega, int k) {
    std::vector<double> out;
    for (const analytic::Vec3& w : omega) {
      const double along = std::abs(w[k]), across = std::hypot(w[(k + 1) % 3], w[(k + 2) % 3]);
      out.push_back(std::atan2(across, along));
    }
    return out;
  }

  void add_stable_spin(ObserverResult& r, const Body& body) const {
    const std::string name = std::string("spin_") + kAxisNames[body.axis];
    const std::vector<double> sim = angles_from_axis(body.omega, body.axis);
    const std::vector<double> exact = angles_from_axis(exact_omega(body), body.axis);
    const double largest = *std::max_element(sim.begin(), sim.end());
    add_metric(r, limits_, name + "_angle", largest);
    add_metric(r, limits_, name + "_angle_ratio", largest / *std::max_element(exact.begin(), exact.end()));
    r.series.push_back({name + "_angle_sim", "t [s]", "angle of omega from its axis [rad]", t_, sim});
    r.series.push_back({name + "_angle_exact", "t [s]", "angle of omega from its axis [rad]", t_, exact});
    r.plots.push_back({name + ".png", std::string("Spin about the ") + kAxisNames[body.axis] + " axis: angle of omega from it",
                       "t [s]", "angle [rad]",
                       {{name + "_angle_sim", "SPH rigid cluster", "line"}, {name + "_angle_exact", "Euler's equations (GSL rk8pd)", "line"}}});
  }

  void add_flip(ObserverResult& r, const Body& body) const {
    std::vector<double> sim, exact;
    for (const analytic::Vec3& w : body.omega) sim.push_back(w[1]);
    for (const analytic::Vec3& w : exact_omega(body)) exact.push_back(w[1]);
    const std::vector<double> flips = analytic::sign_changes(t_, sim);
    const analytic::Vec3 I{body.start.moments[0], body.start.moments[1], body.start.moments[2]};
    const double period = analytic::torque_free_period(I, body.omega.front());
    add_metric(r, limits_, "flip_count", static_cast<double>(flips.size()));
    add_metric(r, limits_, "flip_period_error", std::abs(analytic::period_from_sign_changes(flips) / period - 1.0));
    add_metric(r, limits_, "flip_period", period);
    r.series.push_back({"flip_omega_sim", "t [s]", "omega_2 [rad/s]", t_, sim});
    r.series.push_back({"flip_omega_exact", "t [s]", "omega_2 [rad/s]", t_, exact});
    r.plots.push_back({"flip.png", "Spin about the intermediate axis: omega along it flips (Dzhanibekov)", "t [s]",
                       "omega_2 [rad/s]",
                       {{"flip_omega_sim", "SPH rigid cluster", "line"}, {"flip_omega_exact", "Euler's equations (GSL rk8pd)", "line"}}});
  }

  void add_drift_series(ObserverResult& r) const {
    std::vector<double> drift(t_.size(), 0.0);
    for (const Body& body : bodies_)
      for (std::size_t n = 0; n < t_.size(); ++n) drift[n] = std::max({drift[n], body.L_magnitude[n], body.L_direction[n]});
    r.series.push_back({"L_drift_sim", "t [s]", "max(||L|/|L0| - 1|, angle(L, L0))", t_, drift});
    r.plots.push_back({"angular_momentum.png", "Angular momentum of the three bodies (conserved without torque)", "t [s]",
                       "relative drift", {{"L_drift_sim", "SPH rigid clusters", "line"}}});
  }

  std::vector<Body> bodies_;
  std::vector<double> t_;
  int cluster_count_max_ = 0, loose_sand_max_ = 0;
  std::map<std::string, MetricLimit> limits_;
};

}  // namespace

template <int D>
std::unique_ptr<Observer<D>> make_rigid_spin_observer(const ObserverContext& ctx) {
  if constexpr (D == 3) {
    return std::make_unique<RigidSpinObserver>(ctx);
  } else {
    throw InputError(ctx.spec.file, "/dimension", "the rigid_spin observer needs \"dimension\": 3 (a 2-D body cannot precess)");
  }
}
template std::unique_ptr<Observer<2>> make_rigid_spin_observer<2>(const ObserverContext&);
template std::unique_ptr<Observer<3>> make_rigid_spin_observer<3>(const ObserverContext&);

}  // namespace sc
