// Observer "column_collapse": a 2-D granular column of length L0 and height H0 (the first block)
// collapses against the tank's x- wall on a rough floor (docs/references.md §3, Bui et al. 2008 geometry;
// Lube et al. 2005 and Lajeunesse et al. 2005 runout laws). At the end of the run:
//   runout_normalised       (L∞ − L0)/L0, L∞ the 99th percentile of sand x from the back wall;
//   back_wall_height_ratio  height of the deposit within two spacings of the back wall / H0;
//   rest_energy_ratio       final kinetic energy / its peak (the deposit must be at rest);
// with porous sand and water (wet_sand_collapse), also the water balance of docs/references.md §8:
//   water_balance_rel_error, saturation_violation (porous_probe.hpp). Method-neutral: SPH's porous
//   sand and DEM's grains both show their water in the view's porosity, pore volume and held water.
// Series: the final surface profile against the initial column and the reference bands.
#include <cmath>

#include "observer.hpp"
#include "observers/porous_probe.hpp"
#include "observers/sand_deposit.hpp"

namespace sc {

namespace {

template <int D>
class ColumnCollapseObserver : public Observer<D> {
 public:
  explicit ColumnCollapseObserver(const ObserverContext& ctx) : dx_(ctx.spacing) {
    JsonObject o = validation_block(ctx);
    if (!ctx.spec.tank || ctx.spec.blocks.empty() || ctx.spec.blocks.front().fill != BlockFill::Sand)
      o.fail("observer", "the column_collapse observer needs a tank and a sand block first");
    runout_band_ = o.numbers("runout_band", 2);
    limits_ = read_metric_limits(o);
    o.finish();
    wall_ = ctx.spec.tank->min[0];
    floor_ = ctx.spec.tank->min[D - 1];
    L0_ = ctx.spec.blocks.front().max[0] - wall_;
    H0_ = ctx.spec.blocks.front().max[D - 1] - floor_;
    columns_ = static_cast<std::size_t>(std::ceil((ctx.spec.tank->max[0] - wall_) / dx_));
    if (ctx.spec.porous) fluid_density_ = ctx.spec.porous->fluid_density;
  }

  void sample(const Method<D>& run) override {
    const ParticleView<D> ps = run.particles();
    const double e = sand_kinetic_energy(ps);
    peak_energy_ = std::max(peak_energy_, e);
    time_.push_back(run.time());
    energy_.push_back(e);
    if (fluid_density_ && (water_.has_value() || total_water(ps) > 0.0)) {
      if (!water_) water_.emplace(*fluid_density_);
      water_->sample(run);
      water_total_.push_back(total_water(ps));
    }
  }

  ObserverResult finish(const Method<D>& run) override {
    const ParticleView<D> ps = run.particles();
    ObserverResult r;
    const double runout = quantile(sand_x(ps), 0.99) + 0.5 * dx_ - wall_;
    const std::vector<double> top = surface_heights(ps, wall_, dx_, columns_, floor_);
    const double back = std::max(top[0], columns_ > 1 ? top[1] : 0.0);
    add_metric(r, limits_, "runout_normalised", (runout - L0_) / L0_);
    add_metric(r, limits_, "back_wall_height_ratio", back / H0_);
    add_metric(r, limits_, "rest_energy_ratio", peak_energy_ > 0.0 ? energy_.back() / peak_energy_ : NAN);
    if (water_) {
      add_metric(r, limits_, "water_balance_rel_error", water_->relative_error());
      add_metric(r, limits_, "saturation_violation", water_->saturation_violation());
    }
    std::vector<double> xs, hs;
    for (std::size_t k = 0; k < columns_; ++k) {
      xs.push_back((k + 0.5) * dx_ / L0_);
      hs.push_back(top[k] / H0_);
    }
    const double lo = 1.0 + runout_band_[0], hi = 1.0 + runout_band_[1];
    r.series = {{"deposit_sim", "x / L0", "height / H0", xs, hs},
                {"initial_column", "x / L0", "height / H0", {0.0, 1.0, 1.0}, {1.0, 1.0, 0.0}},
                {"runout_band", "x / L0", "height / H0", {lo, lo, hi, hi}, {0.0, 0.15, 0.15, 0.0}},
                {"back_wall_band", "x / L0", "height / H0", {0.0, 0.0}, {0.95, 1.05}},
                {"energy_sim", "t [s]", "kinetic energy / peak", time_, normalised_energy()}};
    r.plots = {{"deposit.png", "Granular column collapse (a = H0/L0): final deposit", "x / L0", "height / H0",
                {{"deposit_sim", "simulated deposit", "line"}, {"initial_column", "initial column", "line"},
                 {"runout_band", "runout band (Lube 2005 / Lajeunesse 2005)", "line"},
                 {"back_wall_band", "back wall H0 ± 5% (Bui 2008)", "markers"}}},
               {"energy.png", "Kinetic energy of the sand", "t [s]", "E / E_peak", {{"energy_sim", "simulated", "line"}}}};
    if (water_) {
      r.series.push_back({"water_balance_sim", "t [s]", "relative change of free + absorbed water", time_, water_change()});
      r.plots.push_back({"water_balance.png", "Water balance (docs/references.md §8: exact)", "t [s]",
                         "(W(t) - W(0)) / W(0)", {{"water_balance_sim", "free + absorbed water", "line"}}});
    }
    return r;
  }

 private:
  std::vector<double> normalised_energy() const {
    std::vector<double> out;
    for (double e : energy_) out.push_back(peak_energy_ > 0.0 ? e / peak_energy_ : 0.0);
    return out;
  }

  std::vector<double> water_change() const {
    std::vector<double> out;
    for (double w : water_total_) out.push_back(w / water_total_.front() - 1.0);
    return out;
  }

  double dx_, wall_, floor_, L0_, H0_;
  std::size_t columns_;
  std::vector<double> runout_band_;
  double peak_energy_ = 0.0;
  std::vector<double> time_, energy_;
  std::map<std::string, MetricLimit> limits_;
  std::optional<double> fluid_density_;        ///< ρ^f of absorbed water (cases with a "porous" section)
  std::optional<WaterBalanceProbe<D>> water_;  ///< runs with porous sand and water only
  std::vector<double> water_total_;            ///< free + absorbed water at every sample
};

}  // namespace

template <int D>
std::unique_ptr<Observer<D>> make_column_collapse_observer(const ObserverContext& ctx) {
  return std::make_unique<ColumnCollapseObserver<D>>(ctx);
}
template std::unique_ptr<Observer<2>> make_column_collapse_observer<2>(const ObserverContext&);
template std::unique_ptr<Observer<3>> make_column_collapse_observer<3>(const ObserverContext&);

}  // namespace sc
