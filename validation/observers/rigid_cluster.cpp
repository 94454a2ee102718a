// Observer "rigid_cluster": a rigid cluster of the simulated solver against exact rigid-body
// mechanics (docs/references.md §6). A cohesive sand block (the first block, one cluster) falls
// freely: its centre of mass must follow x0 + g t²/2 and it must stay one cluster.
//   free_fall_error              max |y_cm − y_exact| / (g T²/2) of the simulated block;
//   cluster_count_max            most clusters of the simulated block in a step (1: it stayed rigid).
// The rigid-body identities of the cluster code (eqs 12b-18: inertia of a lattice, a = F/M,
// α = I⁻¹τ, conservation of L without torque, the intermediate-axis flip against the exact
// torque-free solution) are unit tests of solver/sand/ (tests/test_sand.cpp, tests/test_rigid_motion.cpp).
#include "observer.hpp"
#include "simulator/sph_probe.hpp"

namespace sc {

namespace {

template <int D>
class RigidClusterObserver : public Observer<D> {
 public:
  explicit RigidClusterObserver(const ObserverContext& ctx) {
    JsonObject o = validation_block(ctx);
    if (ctx.spec.blocks.empty() || ctx.spec.blocks.front().fill != BlockFill::Sand)
      o.fail("observer", "the rigid_cluster observer needs a sand block first");
    require_sph(ctx.spec, "the rigid_cluster observer (it counts SPH's rigid clusters)");
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
