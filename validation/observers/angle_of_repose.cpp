// Observer "angle_of_repose": a pile of cohesionless sand on a rough floor comes to rest at the slope
// angle θ_r = φ (docs/references.md §3: tan θ_r = μ_f for a Mohr-Coulomb material). At the end of the
// run the free surface (top of the sand in columns one spacing wide) is fitted by a straight line
// between 20 % and 80 % of the pile height on each flank (left: rising, right: falling):
//   repose_angle_deg        mean of the two flank angles [deg];
//   repose_angle_left_deg, repose_angle_right_deg;
//   rest_energy_ratio       final kinetic energy / its peak.
// Series: the final surface profile, the fit window, the two flank fits and the band φ ± 3° of the gate
// (lines through each fit's centroid).
#include <cmath>
#include <numeric>

#include "observer.hpp"
#include "observers/sand_deposit.hpp"

namespace sc {

namespace {

template <int D>
class AngleOfReposeObserver : public Observer<D> {
 public:
  explicit AngleOfReposeObserver(const ObserverContext& ctx) : dx_(ctx.spacing) {
    JsonObject o = validation_block(ctx);
    if (!ctx.spec.tank || !ctx.spec.has_sand) o.fail("observer", "the angle_of_repose observer needs a tank and sand");
    limits_ = read_metric_limits(o);
    o.finish();
    x0_ = ctx.spec.tank->min[0];
    floor_ = ctx.spec.tank->min[D - 1];
    columns_ = static_cast<std::size_t>(std::ceil((ctx.spec.tank->max[0] - x0_) / dx_));
    phi_ = ctx.spec.sand.friction_angle_deg;
  }

  void sample(const Method<D>& run) override {
    const double e = sand_kinetic_energy(run.particles());
    peak_energy_ = std::max(peak_energy_, e);
    last_energy_ = e;
  }

  ObserverResult finish(const Method<D>& run) override {
    ObserverResult r;
    const std::vector<double> top = surface_heights(run.particles(), x0_, dx_, columns_, floor_);
    const std::size_t peak = static_cast<std::size_t>(std::max_element(top.begin(), top.end()) - top.begin());
    const double H = top[peak];
    std::vector<double> xl, yl, xr, yr, xs;
    for (std::size_t k = 0; k < columns_; ++k) {
      const double x = x0_ + (k + 0.5) * dx_;
      xs.push_back(x);
      if (top[k] < 0.2 * H || top[k] > 0.8 * H) continue;
      (k < peak ? xl : xr).push_back(x);
      (k < peak ? yl : yr).push_back(top[k]);
    }
    const double left = std::atan(std::abs(fitted_slope(xl, yl))) * 180.0 / pi;
    const double right = std::atan(std::abs(fitted_slope(xr, yr))) * 180.0 / pi;
    add_metric(r, limits_, "repose_angle_deg", 0.5 * (left + right));
    add_metric(r, limits_, "repose_angle_left_deg", left);
    add_metric(r, limits_, "repose_angle_right_deg", right);
    add_metric(r, limits_, "rest_energy_ratio", peak_energy_ > 0.0 ? last_energy_ / peak_energy_ : NAN);
    r.series = {{"surface_sim", "x [m]", "height [m]", xs, top}};
    add_flank_lines(r.series, "left", xl, yl, H, +1.0);
    add_flank_lines(r.series, "right", xr, yr, H, -1.0);
    r.plots = {{"pile.png", "Sand pile at rest: flank fits (20-80% of the height) against phi +- 3 deg", "x [m]",
                "height [m]",
                {{"surface_sim", "simulated sand surface", "line"},
                 {"flank_fit_left", "left flank fit", "line"},
                 {"flank_fit_right", "right flank fit", "line"},
                 {"band_left", "gate band phi +- 3 deg (left)", "line"},
                 {"band_right", "gate band phi +- 3 deg (right)", "line"}}}};
    return r;
  }

 private:
  /// Appends the series flank_fit_<flank> (the fitted line of one flank between 20 % and 80 % of the
  /// height H; rising flank: side = +1, falling: −1) and band_<flank> (the outline of the region
  /// between the lines at φ − 3° and φ + 3° through the fit's centroid (x̄, ȳ), which lies on the
  /// least-squares line): the fit is within the gate where it lies inside the band.
  void add_flank_lines(std::vector<Series>& series, const std::string& flank, const std::vector<double>& x,
                       const std::vector<double>& y, double H, double side) const {
    if (x.size() < 2) return;
    const double xm = std::accumulate(x.begin(), x.end(), 0.0) / x.size();
    const double ym = std::accumulate(y.begin(), y.end(), 0.0) / y.size();
    auto at = [&](double h, double slope) { return xm + side * (h - ym) / slope; };
    const double fit = std::abs(fitted_slope(x, y));
    const double lo = std::tan((phi_ - 3.0) * pi / 180.0), hi = std::tan((phi_ + 3.0) * pi / 180.0);
    const double h0 = 0.2 * H, h1 = 0.8 * H;
    series.push_back({"flank_fit_" + flank, "x [m]", "height [m]", {at(h0, fit), at(h1, fit)}, {h0, h1}});
    series.push_back({"band_" + flank, "x [m]", "height [m]",
                      {at(h0, lo), at(h1, lo), at(h1, hi), at(h0, hi), at(h0, lo)}, {h0, h1, h1, h0, h0}});
  }

  double dx_, x0_, floor_, phi_;
  std::size_t columns_;
  double peak_energy_ = 0.0, last_energy_ = 0.0;
  std::map<std::string, MetricLimit> limits_;
};

}  // namespace

template <int D>
std::unique_ptr<Observer<D>> make_angle_of_repose_observer(const ObserverContext& ctx) {
  return std::make_unique<AngleOfReposeObserver<D>>(ctx);
}
template std::unique_ptr<Observer<2>> make_angle_of_repose_observer<2>(const ObserverContext&);
template std::unique_ptr<Observer<3>> make_angle_of_repose_observer<3>(const ObserverContext&);

}  // namespace sc
