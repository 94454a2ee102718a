// Observer "hydrostatic": a tank of water at rest (docs/references.md §1).
// After `settle_time`, over the last `average_time` seconds, averages the pressure of water
// particles in horizontal bins one spacing high over the central half of the tank width, and
// compares with p(z) = ρ0 g (H − z), excluding two spacings at the floor and at the surface.
// H is the measured free surface: the height where the SPH colour field Σ_j V_j W(|x − x_j|, h_j)
// (1 inside the water) falls to 1/2, averaged over five verticals across the central half, at the
// end of the run. (The top particle row plus dx/2 locates it only to about ±dx/2, depending on the
// packing of that row; it is reported as surface_height.)
// Metrics: pressure_l2 (relative L2 error), surface_drift (relative change of the measured surface
// over the averaging window), spurious_speed (root-mean-square water speed over the window,
// / sqrt(g H): the kinetic energy left in a fluid that should be at rest), spurious_speed_max
// (the largest particle speed in the window / sqrt(g H), informational: single surface particles
// jiggle at a few mm/s).
#include <algorithm>
#include <cmath>

#include "observer.hpp"
#include "reference/analytic/hydrostatic.hpp"
#include "sph/kernels.hpp"

namespace sc {

namespace {

template <int D>
class HydrostaticObserver : public Observer<D> {
 public:
  explicit HydrostaticObserver(const ObserverContext& ctx) : dx_(ctx.spacing) {
    JsonObject o = validation_block(ctx);
    if (!ctx.spec.tank) o.fail("observer", "the hydrostatic observer needs a tank");
    average_time_ = o.positive("average_time");
    limits_ = read_metric_limits(o);
    o.finish();
    const double end = ctx.spec.end_time;
    start_average_ = end - average_time_;
    if (start_average_ <= 0.0) o.fail("average_time", "must be shorter than the run (time.end)");
    floor_ = ctx.spec.tank->min[D - 1];
    const double x0 = ctx.spec.tank->min[0], x1 = ctx.spec.tank->max[0];
    band_lo_ = x0 + 0.25 * (x1 - x0);
    band_hi_ = x0 + 0.75 * (x1 - x0);
    rho0_ = ctx.spec.water.rest_density;
    g_ = std::abs(ctx.spec.gravity[D - 1]);
    kernel_ = ctx.spec.water.density_kernel;
    for (int d = 0; d < D; ++d) centre_[d] = 0.5 * (ctx.spec.tank->min[d] + ctx.spec.tank->max[d]);
  }

  /// Free-surface height: where the colour field Σ_j V_j W_j drops to 1/2 (bisection along a
  /// vertical at x), averaged over five verticals across the central band.
  double colour_surface(const ParticleView<D>& ps, double top) const {
    double sum = 0.0;
    for (int k = 0; k < 5; ++k) {
      Vec<D> x = Vec<D>::Zero();
      x[0] = band_lo_ + (k + 0.5) / 5.0 * (band_hi_ - band_lo_);
      for (int d = 1; d < D - 1; ++d) x[d] = centre_[d];
      double lo = top - 3.0 * dx_, hi = top + 3.0 * dx_;
      for (int it = 0; it < 50; ++it) {
        x[D - 1] = 0.5 * (lo + hi);
        (colour(ps, x) > 0.5 ? lo : hi) = x[D - 1];
      }
      sum += 0.5 * (lo + hi);
    }
    return sum / 5.0 - floor_;
  }

  /// Needs the view's density and support (the particle volume m/ρ and the kernel's radius).
  double colour(const ParticleView<D>& ps, const Vec<D>& x) const {
    double c = 0.0;
    for (std::size_t j = 0; j < ps.size(); ++j)
      if (ps.phase_of(j) == Phase::Water)
        c += ps.m[j] / ps.density[j] * kernel::density_kernel<D>(kernel_, (x - ps.x[j]).norm(), ps.support[j]);
    return c;
  }

  void sample(const Method<D>& run) override {
    const ParticleView<D> ps = run.particles();
    double top = -INFINITY, vmax = 0.0;
    for (std::size_t i = 0; i < ps.size(); ++i) {
      if (ps.phase_of(i) != Phase::Water) continue;
      vmax = std::max(vmax, ps.v[i].norm());
      if (in_band(ps.x[i])) top = std::max(top, ps.x[i][D - 1]);
    }
    const double H = top + 0.5 * dx_ - floor_;
    time_.push_back(run.time());
    height_.push_back(H);
    speed_.push_back(vmax);
    if (run.time() < start_average_) return;
    if (H_window_start_ < 0.0) H_window_start_ = H;
    ++samples_;
    max_speed_window_ = std::max(max_speed_window_, vmax);
    for (std::size_t i = 0; i < ps.size(); ++i)
      if (ps.phase_of(i) == Phase::Water) {
        speed2_sum_ += ps.v[i].squaredNorm();
        ++speed2_count_;
      }
    for (std::size_t i = 0; i < ps.size(); ++i) {
      if (ps.phase_of(i) != Phase::Water || !in_band(ps.x[i])) continue;
      const auto bin = static_cast<std::size_t>(std::max(0.0, (ps.x[i][D - 1] - floor_) / dx_));
      if (bin >= p_sum_.size()) { p_sum_.resize(bin + 1, 0.0); p_count_.resize(bin + 1, 0); }
      p_sum_[bin] += ps.pressure[i];
      ++p_count_[bin];
    }
  }

  ObserverResult finish(const Method<D>& run) override {
    ObserverResult r;
    const double H = samples_ > 0 ? colour_surface(run.particles(), floor_ + height_.back() - 0.5 * dx_) : NAN;
    Series simulated{"pressure_sim", "pressure [Pa]", "height above floor [m]", {}, {}};
    Series exact{"pressure_exact", "pressure [Pa]", "height above floor [m]", {}, {}};
    double err2 = 0.0, ref2 = 0.0;
    for (std::size_t b = 0; b < p_sum_.size(); ++b) {
      if (p_count_[b] == 0) continue;
      const double z = (b + 0.5) * dx_;
      const double p = p_sum_[b] / p_count_[b];
      const double pe = analytic::hydrostatic_pressure(rho0_, g_, H, z);
      simulated.x.push_back(p); simulated.y.push_back(z);
      exact.x.push_back(pe); exact.y.push_back(z);
      if (z < 2.0 * dx_ || z > H - 2.0 * dx_) continue;
      err2 += (p - pe) * (p - pe);
      ref2 += pe * pe;
    }
    const double H_end = height_.empty() ? NAN : height_.back();
    add(r, "pressure_l2", ref2 > 0.0 ? std::sqrt(err2 / ref2) : NAN);
    add(r, "surface_drift", std::abs(H_end - H_window_start_) / H);
    add(r, "spurious_speed", std::sqrt(speed2_sum_ / std::max(1L, speed2_count_)) / std::sqrt(g_ * H));
    add(r, "spurious_speed_max", max_speed_window_ / std::sqrt(g_ * H));
    add(r, "surface_height", H_end);
    add(r, "colour_surface_height", H);
    r.series = {simulated, exact,
                {"surface_height", "time [s]", "surface height [m]", time_, height_},
                {"max_speed", "time [s]", "largest water speed [m/s]", time_, speed_}};
    r.plots = {{"pressure_profile.png", "Hydrostatic pressure, averaged over the last " + format_number(average_time_) + " s",
                "pressure [Pa]", "height above floor [m]",
                {{"pressure_sim", "simulated (bin average)", "markers"}, {"pressure_exact", "rho0 g (H - z)", "line"}}},
               {"surface_and_speed.png", "Surface height", "time [s]", "surface height [m]",
                {{"surface_height", "measured H", "line"}}},
               {"max_speed.png", "Largest water speed", "time [s]", "speed [m/s]", {{"max_speed", "max |v|", "line"}}}};
    return r;
  }

 private:
  bool in_band(const Vec<D>& x) const { return x[0] >= band_lo_ && x[0] <= band_hi_; }
  void add(ObserverResult& r, const std::string& name, double value) const { add_metric(r, limits_, name, value); }

  double dx_, average_time_, start_average_, floor_, band_lo_, band_hi_, rho0_, g_;
  std::map<std::string, MetricLimit> limits_;
  std::vector<double> time_, height_, speed_, p_sum_;
  std::vector<long> p_count_;
  kernel::DensityKernel kernel_;
  Vec<D> centre_;
  double H_window_start_ = -1.0, max_speed_window_ = 0.0;
  long samples_ = 0, speed2_count_ = 0;
  double speed2_sum_ = 0.0;
};

}  // namespace

template <int D>
std::unique_ptr<Observer<D>> make_hydrostatic_observer(const ObserverContext& ctx) {
  return std::make_unique<HydrostaticObserver<D>>(ctx);
}
template std::unique_ptr<Observer<2>> make_hydrostatic_observer<2>(const ObserverContext&);
template std::unique_ptr<Observer<3>> make_hydrostatic_observer<3>(const ObserverContext&);

}  // namespace sc
