// Observer "scene": the smoke check of a showcase scene (thesis scenes, benchmarks), which has no
// reference solution. Metrics: `escaped`, the number of moving particles that end up outside the
// tank (more than one spacing beyond a closed wall) or outside the domain; `water_mass_change`,
// the relative change of the free-water mass (informational: the porous engineer's absorbed mass
// still has to join it before it can be a water balance).
#include <cmath>

#include "observer.hpp"

namespace sc {

namespace {

template <int D>
class SceneObserver : public Observer<D> {
 public:
  explicit SceneObserver(const ObserverContext& ctx) : spec_(ctx.spec), dx_(ctx.spacing) {
    JsonObject o = validation_block(ctx);
    limits_ = read_metric_limits(o);
    o.finish();
  }

  void sample(const Simulator<D>& sim) override {
    time_.push_back(sim.time());
    water_mass_.push_back(water_mass(sim.particles()));
  }

  ObserverResult finish(const Simulator<D>& sim) override {
    ObserverResult r;
    add_metric(r, limits_, "escaped", static_cast<double>(escaped(sim.particles())));
    add_metric(r, limits_, "water_mass_change", water_mass_.front() > 0.0 ? water_mass_.back() / water_mass_.front() - 1.0 : 0.0);
    r.series.push_back({"water_mass_sim", "t [s]", "free water mass [kg]", time_, water_mass_});
    r.plots.push_back({"water_mass.png", spec_.name + ": free water mass", "t [s]", "mass [kg]", {{"water_mass_sim", "simulation", "line"}}});
    return r;
  }

 private:
  static double water_mass(const ParticleSet<D>& ps) {
    double m = 0.0;
    for (std::size_t i = 0; i < ps.size(); ++i)
      if (ps.phase_of(i) == Phase::Water) m += ps.m[i];
    return m;
  }

  bool outside(const Vec<D>& x) const {
    const char* axes = "xyz";
    for (int d = 0; d < D; ++d) {
      if (x[d] < spec_.domain_min[d] || x[d] > spec_.domain_max[d]) return true;
      if (!spec_.tank) continue;
      const std::string axis(1, axes[d]);
      if (spec_.tank->sides.at(axis + "-") != "open" && x[d] < spec_.tank->min[d] - dx_) return true;
      if (spec_.tank->sides.at(axis + "+") != "open" && x[d] > spec_.tank->max[d] + dx_) return true;
    }
    return false;
  }

  long escaped(const ParticleSet<D>& ps) const {
    long n = 0;
    for (std::size_t i = 0; i < ps.size(); ++i)
      if (ps.moves(i) && outside(ps.x[i])) ++n;
    return n;
  }

  const CaseSpec& spec_;
  double dx_;
  std::map<std::string, MetricLimit> limits_;
  std::vector<double> time_, water_mass_;
};

}  // namespace

template <int D>
std::unique_ptr<Observer<D>> make_scene_observer(const ObserverContext& ctx) {
  return std::make_unique<SceneObserver<D>>(ctx);
}
template std::unique_ptr<Observer<2>> make_scene_observer<2>(const ObserverContext&);
template std::unique_ptr<Observer<3>> make_scene_observer<3>(const ObserverContext&);

}  // namespace sc
