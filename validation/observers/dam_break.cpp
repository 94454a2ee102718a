// Observer "dam_break": surge front and residual height of a collapsing water column against
// Martin & Moyce 1952 (docs/references.md §2). The column of width a (the first block) stands against
// the tank's x- wall on its floor. Every step records
//   front  Z = x_front / a, with x_front the largest x (plus half a spacing) of water particles
//          within 2 spacings of the floor having at least a third of the bulk neighbour count in
//          water neighbours (isolated spray does not count), against T = t sqrt(g/a);
//   height H = y_max / a (plus half a spacing) of water within 2 spacings of the back wall, with the
//          same neighbour-count filter (a droplet clinging to the wall does not count), against
//          tau = t sqrt(g/a).
// Metrics: front_rms and front_max (relative errors of Z at the table's T, no time shift) and
// residual_height_rms (relative, tau <= 3).
// The neighbour count is taken on the particles' current positions (support radius h of the case's
// spacing), so the observer measures any method the same way.
#include <algorithm>
#include <cmath>

#include "observer.hpp"
#include "reference_data.hpp"
#include "scene/scene_builder.hpp"
#include "neighbours/cell_grid.hpp"

namespace sc {

namespace {

/// Neighbour count of a particle inside an unbounded lattice (self included).
template <int D>
long bulk_neighbour_count(double dx, double h) {
  long count = 0;
  const Vec<D> lo = Vec<D>::Constant(-h - 0.5 * dx), hi = Vec<D>::Constant(h + 0.5 * dx);
  for (const auto& p : lattice_points<D>(lo, hi, dx)) count += p.norm() <= h ? 1 : 0;
  return count;
}

/// For each water particle (in index order), the water particles within h of it, itself included.
template <int D>
std::vector<long> water_neighbour_counts(const ParticleView<D>& ps, double h, std::vector<Vec<D>>& water) {
  water.clear();
  for (std::size_t i = 0; i < ps.size(); ++i)
    if (ps.phase_of(i) == Phase::Water) water.push_back(ps.x[i]);
  std::vector<long> count(water.size(), 0);
  if (water.empty()) return count;
  CellGrid<D> grid;
  grid.build(water, h);
  for (std::size_t k = 0; k < water.size(); ++k)
    grid.for_each_near(water[k], [&](std::uint32_t j) { count[k] += (water[j] - water[k]).norm() <= h ? 1 : 0; });
  return count;
}

template <int D>
class DamBreakObserver : public Observer<D> {
 public:
  explicit DamBreakObserver(const ObserverContext& ctx) : dx_(ctx.spacing) {
    JsonObject o = validation_block(ctx);
    if (!ctx.spec.tank || ctx.spec.blocks.empty()) o.fail("observer", "the dam_break observer needs a tank and a water block");
    const std::string front_csv = o.string("front_reference");
    const std::string height_csv = o.string("height_reference");
    height_tau_max_ = o.positive("height_tau_max", 3.0);
    limits_ = read_metric_limits(o);
    o.finish();
    front_ref_ = read_reference_csv(ctx.source_dir + "/" + front_csv);
    height_ref_ = read_reference_csv(ctx.source_dir + "/" + height_csv);
    for (const auto* ref : {&front_ref_, &height_ref_})
      if (!ref->count("T") || !ref->count("value"))
        throw InputError(ref == &front_ref_ ? front_csv : height_csv, "", "needs columns T and value");
    x0_ = ctx.spec.tank->min[0];
    y0_ = ctx.spec.tank->min[D - 1];
    a_ = ctx.spec.blocks.front().max[0] - ctx.spec.blocks.front().min[0];
    time_scale_ = std::sqrt(std::abs(ctx.spec.gravity[D - 1]) / a_);
    h_ = resolve(ctx.spec, dx_).h;
    min_neighbours_ = bulk_neighbour_count<D>(dx_, h_) / 3;
  }

  void sample(const Method<D>& run) override {
    const std::vector<long> count = water_neighbour_counts(run.particles(), h_, water_);
    double front = 0.0, height = 0.0;
    for (std::size_t k = 0; k < water_.size(); ++k) {
      const Vec<D>& x = water_[k];
      const bool dense = count[k] >= min_neighbours_;
      if (x[D - 1] - y0_ <= 2.0 * dx_ && dense) front = std::max(front, x[0] - x0_ + 0.5 * dx_);
      if (x[0] - x0_ <= 2.0 * dx_ && dense) height = std::max(height, x[D - 1] - y0_ + 0.5 * dx_);
    }
    T_.push_back(run.time() * time_scale_);
    Z_.push_back(front / a_);
    H_.push_back(height / a_);
  }

  ObserverResult finish(const Method<D>&) override {
    ObserverResult r;
    const double T_end = T_.empty() ? 0.0 : T_.back();
    double sum2 = 0.0, worst = 0.0;
    long n = 0;
    const auto& Tf = front_ref_.at("T");
    const auto& Zf = front_ref_.at("value");
    for (std::size_t k = 0; k < Tf.size(); ++k) {
      if (Tf[k] > T_end) continue;
      const double e = (interpolate_linear(T_, Z_, Tf[k]) - Zf[k]) / Zf[k];
      sum2 += e * e;
      worst = std::max(worst, std::abs(e));
      ++n;
    }
    add_metric(r, limits_, "front_rms", n > 0 ? std::sqrt(sum2 / n) : NAN);
    add_metric(r, limits_, "front_max", n > 0 ? worst : NAN);
    double hsum2 = 0.0;
    long hn = 0;
    const auto& Th = height_ref_.at("T");
    const auto& Hh = height_ref_.at("value");
    for (std::size_t k = 0; k < Th.size(); ++k) {
      if (Th[k] > std::min(T_end, height_tau_max_)) continue;
      const double e = (interpolate_linear(T_, H_, Th[k]) - Hh[k]) / Hh[k];
      hsum2 += e * e;
      ++hn;
    }
    add_metric(r, limits_, "residual_height_rms", hn > 0 ? std::sqrt(hsum2 / hn) : NAN);
    r.series = {{"front_sim", "T = t sqrt(g/a)", "Z = z/a", T_, Z_},
                {"front_martin_moyce", "T = t sqrt(g/a)", "Z = z/a", Tf, Zf},
                {"height_sim", "tau = t sqrt(g/a)", "H = eta/a", T_, H_},
                {"height_martin_moyce", "tau = t sqrt(g/a)", "H = eta/a", Th, Hh}};
    r.plots = {{"front.png", "Surge front, square column (n^2 = 1)", "T = t sqrt(g/a)", "Z = z/a",
                {{"front_sim", "simulated front", "line"}, {"front_martin_moyce", "Martin & Moyce 1952", "markers"}}},
               {"residual_height.png", "Residual height at the back wall", "tau = t sqrt(g/a)", "H = eta/a",
                {{"height_sim", "simulated residual height", "line"}, {"height_martin_moyce", "Martin & Moyce 1952", "markers"}}}};
    return r;
  }

 private:
  double dx_, h_, x0_, y0_, a_, time_scale_, height_tau_max_;
  long min_neighbours_;
  Columns front_ref_, height_ref_;
  std::map<std::string, MetricLimit> limits_;
  std::vector<double> T_, Z_, H_;
  std::vector<Vec<D>> water_;  // positions of the water particles at the last sample
};

}  // namespace

template <int D>
std::unique_ptr<Observer<D>> make_dam_break_observer(const ObserverContext& ctx) {
  return std::make_unique<DamBreakObserver<D>>(ctx);
}
template std::unique_ptr<Observer<2>> make_dam_break_observer<2>(const ObserverContext&);
template std::unique_ptr<Observer<3>> make_dam_break_observer<3>(const ObserverContext&);

}  // namespace sc
