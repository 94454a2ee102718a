// Observer "capillary_rise": a dry fixed porous column standing in a pool (docs/references.md §5).
// The water table is the pool surface (top of the pool's water particles outside the column,
// plus half a spacing), measured at the end. Over the last `average_time` seconds the row means
// of S in the column's central band are averaged into S(z), z above the table, and compared with
// the equilibrium of the capillary potential (eq 23) against gravity, S(z) = 1 − (ρ g z/k^c)^(1/α)
// (reference/analytic/capillary_rise.hpp). The fringe height is where S(z) falls to
// `fringe_saturation` (linear interpolation), compared with z_max (1 − S*)^α; the held water is
// Σ φ S dz above the table against φ k^c / (ρ g (α + 1)).
// Metrics: fringe_height_rel_error, held_volume_rel_error, saturation_profile_l2 (RMS of
// S − S_exact over the rows from the table to z_max), water_balance_rel_error, saturation_violation;
// informational: rise_exponent (slope of log h against log t while the fringe rises from 20 % to
// 60 % of z_max: 0.5 for h² ∝ t), fringe_height, table_height.
#include "observer.hpp"
#include "porous_probe.hpp"
#include "reference/analytic/capillary_rise.hpp"

namespace sc {

namespace {

template <int D>
class CapillaryRiseObserver : public Observer<D> {
 public:
  explicit CapillaryRiseObserver(const ObserverContext& ctx) : dx_(ctx.spacing) {
    JsonObject o = validation_block(ctx);
    if (!ctx.spec.porous) o.fail("observer", "capillary_rise needs a \"porous\" section");
    const std::vector<double> band = o.numbers("column_x", 2);
    bottom_ = o.number("column_bottom");
    top_ = o.number("column_top");
    average_time_ = o.positive("average_time");
    s_star_ = o.in_range("fringe_saturation", 0.0, 1.0, true, 0.5);
    limits_ = read_metric_limits(o);
    o.finish();
    start_average_ = ctx.spec.end_time - average_time_;
    const double quarter = 0.25 * (band[1] - band[0]);
    column_lo_ = band[0];
    column_hi_ = band[1];
    band_lo_ = band[0] + quarter;
    band_hi_ = band[1] - quarter;
    const PorousParams& p = *ctx.spec.porous;
    rho_ = p.fluid_density;
    g_ = std::abs(ctx.spec.gravity[D - 1]);
    kc_ = p.capillary_constant;
    alpha_ = p.capillary_exponent;
    phi_ = p.porosity;
    balance_ = WaterBalanceProbe<D>(p.fluid_density);
    rows_ = static_cast<std::size_t>(std::lround((top_ - bottom_) / dx_));
    s_sum_.assign(rows_, 0.0);
  }

  void sample(const Method<D>& run) override {
    balance_.sample(run);
    const ParticleView<D> ps = run.particles();
    const std::vector<double> s = row_means(ps, ps.saturation, band_lo_, band_hi_, bottom_, dx_, rows_);
    table_ = pool_surface(ps);
    double wet_top = bottom_;
    for (std::size_t k = 0; k < rows_; ++k)
      if (s[k] >= 0.5) wet_top = bottom_ + (k + 1) * dx_;
    time_.push_back(run.time());
    rise_.push_back(wet_top - table_);
    if (run.time() < start_average_) return;
    for (std::size_t k = 0; k < rows_; ++k) s_sum_[k] += s[k];
    ++samples_;
  }

  ObserverResult finish(const Method<D>&) override {
    ObserverResult r;
    const double zmax = analytic::fringe_height(kc_, rho_, g_);
    Series sim_s{"saturation_sim", "saturation S", "height above the table [m]", {}, {}};
    Series ref_s{"saturation_exact", "saturation S", "height above the table [m]", {}, {}};
    double err2 = 0.0, held = 0.0, fringe = NAN, prev_z = NAN, prev_s = NAN;
    long n = 0;
    for (std::size_t k = 0; k < rows_; ++k) {
      const double z = bottom_ + (k + 0.5) * dx_ - table_;
      const double s = s_sum_[k] / std::max(1L, samples_);
      const double se = analytic::equilibrium_saturation(z, kc_, rho_, g_, alpha_);
      sim_s.x.push_back(s); sim_s.y.push_back(z);
      ref_s.x.push_back(se); ref_s.y.push_back(z);
      if (z > 0.0) held += phi_ * s * dx_;
      if (z > 0.0 && z < zmax) { err2 += (s - se) * (s - se); ++n; }
      if (std::isnan(fringe) && z > 0.0 && prev_s >= s_star_ && s < s_star_)
        fringe = prev_z + (prev_s - s_star_) / (prev_s - s) * (z - prev_z);
      prev_z = z;
      prev_s = s;
    }
    const double fringe_ref = analytic::height_at_saturation(s_star_, kc_, rho_, g_, alpha_);
    const double held_ref = analytic::held_water(kc_, rho_, g_, alpha_, phi_);
    add(r, "fringe_height", fringe);
    add(r, "fringe_height_rel_error", std::abs(fringe - fringe_ref) / fringe_ref);
    add(r, "held_volume_rel_error", std::abs(held - held_ref) / held_ref);
    add(r, "saturation_profile_l2", n > 0 ? std::sqrt(err2 / n) : NAN);
    add(r, "table_height", table_);
    add(r, "rise_exponent", rise_exponent(zmax));
    add(r, "water_balance_rel_error", balance_.relative_error());
    add(r, "saturation_violation", balance_.saturation_violation());
    r.series = {sim_s, ref_s, {"rise_sim", "time [s]", "height of S = 1/2 above the table [m]", time_, rise_}};
    r.plots = {{"saturation_profile.png", "Capillary fringe S(z), mean of the last " + format_number(average_time_) + " s",
                "saturation S", "height above the water table [m]",
                {{"saturation_sim", "SPH porous flow (row mean)", "markers"}, {"saturation_exact", "1 - (rho g z / k^c)^(1/alpha)", "line"}}},
               {"rise.png", "Capillary rise", "time [s]", "height [m]", {{"rise_sim", "S = 1/2 level", "line"}}}};
    return r;
  }

 private:
  /// Top of the pool's water outside the column, plus half a spacing.
  double pool_surface(const ParticleView<D>& ps) const {
    double top = -INFINITY;
    for (std::size_t i = 0; i < ps.size(); ++i)
      if (ps.phase_of(i) == Phase::Water && (ps.x[i][0] < column_lo_ - dx_ || ps.x[i][0] > column_hi_ + dx_))
        top = std::max(top, ps.x[i][D - 1]);
    return top + 0.5 * dx_;
  }
  double rise_exponent(double zmax) const {
    std::vector<double> lt, lh;
    for (std::size_t k = 0; k < time_.size(); ++k)
      if (time_[k] > 0.0 && rise_[k] >= 0.2 * zmax && rise_[k] <= 0.6 * zmax) {
        lt.push_back(std::log(time_[k]));
        lh.push_back(std::log(rise_[k]));
      }
    return lt.size() > 2 ? fitted_slope(lt, lh) : NAN;
  }
  void add(ObserverResult& r, const std::string& name, double value) const { add_metric(r, limits_, name, value); }

  double dx_, bottom_, top_, average_time_, s_star_, start_average_, column_lo_, column_hi_, band_lo_, band_hi_;
  double rho_, g_, kc_, alpha_, phi_, table_ = 0.0;
  std::size_t rows_;
  long samples_ = 0;
  std::map<std::string, MetricLimit> limits_;
  WaterBalanceProbe<D> balance_;
  std::vector<double> s_sum_, time_, rise_;
};

}  // namespace

template <int D>
std::unique_ptr<Observer<D>> make_capillary_rise_observer(const ObserverContext& ctx) {
  return std::make_unique<CapillaryRiseObserver<D>>(ctx);
}
template std::unique_ptr<Observer<2>> make_capillary_rise_observer<2>(const ObserverContext&);
template std::unique_ptr<Observer<3>> make_capillary_rise_observer<3>(const ObserverContext&);

}  // namespace sc
