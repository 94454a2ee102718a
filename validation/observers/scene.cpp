// Observer "scene": the smoke check of a showcase scene (thesis scenes, benchmarks), which has no
// reference solution. Metrics: `escaped`, the number of moving particles that end up outside the
// tank (more than one spacing beyond a closed wall) or outside the domain; `water_balance_rel_error`,
// the largest relative change over the run of all water, free (water particles) plus absorbed
// (porous m_p and emission stores; docs/references.md §8: exact up to round-off); `free_water_fraction`,
// the free water at the end over all water (informational: how much the sand drank).
// Collapse of the sculpture (objective form of "standing where dry, collapsing where the water hits
// it"): every sand particle is followed by its id from the start; it counts as wetted once its
// saturation has reached kWetSaturation at some sample, and as displaced when it ends more than
// kDisplacedSpacings particle spacings from where it started. `sand_displaced_fraction_wet` and
// `sand_displaced_fraction_dry` are the displaced fractions of the wetted and of the never-wetted
// sand, `sand_wetted_fraction` the wetted share of all sand. Their limits are applied only to a run
// that reaches the case's time.end (the full tier); a shortened run (the quick smoke run) reports
// them without a gate, since the water has not arrived yet.
#include <algorithm>
#include <cmath>
#include <unordered_map>

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

  void sample(const Method<D>& run) override {
    const ParticleView<D> ps = run.particles();
    follow_sand(ps);
    time_.push_back(run.time());
    free_water_.push_back(free_water(ps));
    all_water_.push_back(total_water(ps));
  }

  ObserverResult finish(const Method<D>& run) override {
    ObserverResult r;
    add_metric(r, limits_, "escaped", static_cast<double>(escaped(run.particles())));
    double balance = 0.0;
    for (double w : all_water_) balance = std::max(balance, std::abs(w - all_water_.front()));
    add_metric(r, limits_, "water_balance_rel_error", all_water_.front() > 0.0 ? balance / all_water_.front() : 0.0);
    add_metric(r, limits_, "free_water_fraction", all_water_.back() > 0.0 ? free_water_.back() / all_water_.back() : 0.0);
    add_collapse_metrics(r, run);
    r.series.push_back({"free_water_sim", "t [s]", "water mass [kg]", time_, free_water_});
    r.series.push_back({"all_water_sim", "t [s]", "water mass [kg]", time_, all_water_});
    r.plots.push_back({"water_mass.png", spec_.name + ": water balance", "t [s]", "mass [kg]",
                       {{"free_water_sim", "free water (particles)", "line"}, {"all_water_sim", "free + absorbed", "line"}}});
    return r;
  }

 private:
  static constexpr double kWetSaturation = 0.1;
  static constexpr double kDisplacedSpacings = 2.0;

  struct SandTrack {
    Vec<D> start;
    bool wetted = false;
  };

  /// Follows each sand particle by its identity; saturation, where the method has it.
  void follow_sand(const ParticleView<D>& ps) {
    const bool first = time_.empty();
    for (std::size_t i = 0; i < ps.size(); ++i) {
      if (ps.phase_of(i) != Phase::Sand) continue;
      if (first) sand_[ps.identity(i)] = SandTrack{ps.x[i]};
      if (!ps.saturation.empty() && ps.saturation[i] >= kWetSaturation) sand_.at(ps.identity(i)).wetted = true;
    }
  }

  void add_collapse_metrics(ObserverResult& r, const Method<D>& run) const {
    const ParticleView<D> ps = run.particles();
    double wet = 0.0, dry = 0.0, wet_moved = 0.0, dry_moved = 0.0;
    for (std::size_t i = 0; i < ps.size(); ++i) {
      if (ps.phase_of(i) != Phase::Sand) continue;
      const SandTrack& t = sand_.at(ps.identity(i));
      const bool moved = (ps.x[i] - t.start).norm() > kDisplacedSpacings * dx_;
      (t.wetted ? wet : dry) += 1.0;
      (t.wetted ? wet_moved : dry_moved) += moved ? 1.0 : 0.0;
    }
    const bool full_length = run.time() >= spec_.end_time - 0.5 * spec_.dt_max;
    const auto& limits = full_length ? limits_ : std::map<std::string, MetricLimit>{};
    add_metric(r, limits, "sand_displaced_fraction_wet", wet > 0.0 ? wet_moved / wet : 0.0);
    add_metric(r, limits, "sand_displaced_fraction_dry", dry > 0.0 ? dry_moved / dry : 0.0);
    add_metric(r, limits, "sand_wetted_fraction", wet + dry > 0.0 ? wet / (wet + dry) : 0.0);
  }

  static double free_water(const ParticleView<D>& ps) {
    double m = 0.0;
    for (std::size_t i = 0; i < ps.size(); ++i)
      if (ps.phase_of(i) == Phase::Water) m += ps.m[i];
    return m;
  }

  bool outside(const Vec<D>& x) const {
    for (int d = 0; d < D; ++d) {
      if (x[d] < spec_.domain_min[d] || x[d] > spec_.domain_max[d]) return true;
      if (!spec_.tank) continue;
      if (spec_.tank->closed(d, -1) && x[d] < spec_.tank->min[d] - dx_) return true;
      if (spec_.tank->closed(d, 1) && x[d] > spec_.tank->max[d] + dx_) return true;
    }
    return false;
  }

  long escaped(const ParticleView<D>& ps) const {
    long n = 0;
    for (std::size_t i = 0; i < ps.size(); ++i)
      if (ps.moves(i) && outside(ps.x[i])) ++n;
    return n;
  }

  const CaseSpec& spec_;
  double dx_;
  std::map<std::string, MetricLimit> limits_;
  std::vector<double> time_, free_water_, all_water_;
  std::unordered_map<std::int64_t, SandTrack> sand_;
};

}  // namespace

template <int D>
std::unique_ptr<Observer<D>> make_scene_observer(const ObserverContext& ctx) {
  return std::make_unique<SceneObserver<D>>(ctx);
}
template std::unique_ptr<Observer<2>> make_scene_observer<2>(const ObserverContext&);
template std::unique_ptr<Observer<3>> make_scene_observer<3>(const ObserverContext&);

}  // namespace sc
