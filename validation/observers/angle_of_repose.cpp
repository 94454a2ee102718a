// Observer "angle_of_repose": a pile of cohesionless sand on a rough floor comes to rest at the slope
// angle θ_r = φ (REFERENCES.md §3: tan θ_r = μ_f for a Mohr-Coulomb material). At the end of the
// run the free surface (top of the sand in columns one spacing wide) is fitted by a straight line
// between 20 % and 80 % of the pile height on each flank (left: rising, right: falling):
//   repose_angle_deg        mean of the two flank angles [deg];
//   repose_angle_left_deg, repose_angle_right_deg;
//   rest_energy_ratio       final kinetic energy / its peak.
// Series: the final surface profile with the two lines at the friction angle through the fits.
#include <cmath>

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

  void sample(const Simulator<D>& sim) override {
    const double e = sand_kinetic_energy(sim.particles());
    peak_energy_ = std::max(peak_energy_, e);
    last_energy_ = e;
  }

  ObserverResult finish(const Simulator<D>& sim) override {
    ObserverResult r;
    const std::vector<double> top = surface_heights(sim.particles(), x0_, dx_, columns_, floor_);
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
    const double t = std::tan(phi_ * pi / 180.0), xp = xs[peak];
    std::vector<double> ref;
    for (double x : xs) ref.push_back(std::max(0.0, H - t * std::abs(x - xp)));
    r.series = {{"surface_sim", "x [m]", "height [m]", xs, top}, {"friction_angle_cone", "x [m]", "height [m]", xs, ref}};
    r.plots = {{"pile.png", "Sand pile at rest against slopes at the friction angle", "x [m]", "height [m]",
                {{"surface_sim", "SPH sand surface", "line"}, {"friction_angle_cone", "slopes tan(phi)", "line"}}}};
    return r;
  }

 private:
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
