// Observer "green_ampt": ponded infiltration into a dry fixed porous bed (docs/references.md §4).
// F(t) is the absorbed water per unit area in the central band of the bed (its water volume as
// the lattice holds it, lattice_water_volume, divided by the band width); the wetting front is the deepest row (band
// mean) with S ≥ 1/2, measured down from the bed surface. Reference: Green-Ampt with
// K_h = k ρ^f g / μ, Δθ = φ (1 − S0) and the suction head ψ = α H_c B(α, β + 2), H_c = k^c/(ρ^f g)
// (reference/analytic/green_ampt.hpp), i.e. the capillary drive of the model's retention curve
// (eq 23) and relative permeability S^{β+1} (eqs 28′-29), under the measured pond depth h(t)
// (the model gives the bed surface the pond's pressure, solver/porous/rigid_pore_pressure.hpp):
// the falling-head Green-Ampt law dF/dt = K (1 + (ψ + h(t)) Δθ / F), started with the
// constant-head solution (GSL Lambert W, suction ψ + h(0)) over the first sample interval and
// integrated with RK4 over the sampled h(t) (linear between samples). Pond depth: the water
// above the bed surface as a height, a full-size water particle being one spacing^D of it
// (lattice_water_volume, the measure of F too).
// Metrics: infiltration_rel_error (largest |F − F_GA|/F_GA over samples with t ≥ 5 ψΔθ/K_h),
// front_depth_rel_error (same window, informational), water_balance_rel_error,
// saturation_violation; informational psi [m], K [m/s], t_gate_start [s]. Samples after the pond
// has run dry (h < one spacing) are left out of the gate (Green-Ampt needs ponding).
// The pond depth counts water in full SPH water particles (the SPH probe): the observer needs SPH.
#include "observer.hpp"
#include "porous_probe.hpp"
#include "simulator/sph_probe.hpp"
#include "reference/analytic/green_ampt.hpp"

namespace sc {

namespace {

template <int D>
class GreenAmptObserver : public Observer<D> {
 public:
  explicit GreenAmptObserver(const ObserverContext& ctx) : dx_(ctx.spacing) {
    JsonObject o = validation_block(ctx);
    if (!ctx.spec.porous || !ctx.spec.tank) o.fail("observer", "green_ampt needs a \"porous\" section and a tank");
    require_sph(ctx.spec, "the green_ampt observer (its pond depth counts full SPH water particles)");
    surface_ = o.number("bed_surface");
    bottom_ = o.number("bed_bottom");
    sample_interval_ = o.positive("sample_interval", 0.05);
    limits_ = read_metric_limits(o);
    o.finish();
    const PorousParams& p = *ctx.spec.porous;
    rho_ = p.fluid_density;
    balance_ = WaterBalanceProbe<D>(p.fluid_density);
    const double g = std::abs(ctx.spec.gravity[D - 1]);
    K_ = p.permeability * rho_ * g / p.fluid_viscosity;
    dtheta_ = p.porosity * (1.0 - p.initial_saturation);
    psi_ = analytic::capillary_drive(p.capillary_constant / (rho_ * g), p.capillary_exponent, p.saturation_exponent);
    const double x0 = ctx.spec.tank->min[0], x1 = ctx.spec.tank->max[0];
    tank_width_ = x1 - x0;
    for (int d = 1; d < D - 1; ++d) tank_width_ *= ctx.spec.tank->max[d] - ctx.spec.tank->min[d];
    band_lo_ = x0 + 0.25 * (x1 - x0);
    band_hi_ = x1 - 0.25 * (x1 - x0);
  }

  void sample(const Method<D>& run) override {
    balance_.sample(run);
    if (run.time() < next_sample_ - 1e-12) return;
    next_sample_ += sample_interval_;
    const ParticleView<D> ps = run.particles();
    const double water_mass = require_sph(run, "green_ampt").full_water_mass();
    double water = 0.0, pond = 0.0;
    std::vector<double> S(ps.size(), 0.0);
    for (std::size_t i = 0; i < ps.size(); ++i) {
      if (ps.phase_of(i) == Phase::Water && ps.x[i][D - 1] > surface_) pond += ps.m[i];
      if (!in_porous_band(ps, i, band_lo_, band_hi_)) continue;
      water += ps.water_held_by(i);
      S[i] = ps.saturation[i];
    }
    if (time_.empty()) initial_ = water;
    const auto rows = static_cast<std::size_t>(std::lround((surface_ - bottom_) / dx_));
    const std::vector<double> s_rows = row_means(ps, S, band_lo_, band_hi_, bottom_, dx_, rows);
    double front = 0.0;
    for (std::size_t k = 0; k < rows; ++k)
      if (s_rows[k] >= 0.5) front = std::max(front, surface_ - (bottom_ + k * dx_));
    time_.push_back(run.time());
    F_.push_back(lattice_water_volume<D>(water - initial_, water_mass, dx_) / band_width());
    front_.push_back(front);
    pond_.push_back(lattice_water_volume<D>(pond, water_mass, dx_) / tank_width_);
  }

  ObserverResult finish(const Method<D>&) override {
    ObserverResult r;
    const double t_min = 5.0 * psi_ * dtheta_ / K_;
    double err = 0.0, front_err = 0.0;
    Series F_ga{"infiltration_exact", "time [s]", "cumulative infiltration F [m]", {}, {}};
    Series z_ga{"front_exact", "time [s]", "front depth [m]", {}, {}};
    const std::vector<double> F_ref = falling_head_reference();
    for (std::size_t k = 0; k < time_.size(); ++k) {
      const double F = F_ref[k];
      F_ga.x.push_back(time_[k]); F_ga.y.push_back(F);
      z_ga.x.push_back(time_[k]); z_ga.y.push_back(analytic::green_ampt_front_depth(F, dtheta_));
      if (time_[k] < t_min || pond_[k] < dx_) continue;
      err = std::max(err, std::abs(F_[k] - F) / F);
      front_err = std::max(front_err, std::abs(front_[k] - z_ga.y.back()) / z_ga.y.back());
    }
    const bool reached = !time_.empty() && time_.back() >= t_min;
    add(r, "infiltration_rel_error", reached ? err : NAN);
    add(r, "front_depth_rel_error", reached ? front_err : NAN);
    add(r, "water_balance_rel_error", balance_.relative_error());
    add(r, "saturation_violation", balance_.saturation_violation());
    add(r, "psi", psi_);
    add(r, "K", K_);
    add(r, "t_gate_start", t_min);
    r.series = {{"infiltration_sim", "time [s]", "cumulative infiltration F [m]", time_, F_}, F_ga,
                {"front_sim", "time [s]", "front depth [m]", time_, front_}, z_ga,
                {"pond_depth", "time [s]", "pond depth [m]", time_, pond_}};
    r.plots = {{"infiltration.png", "Cumulative infiltration F(t), gate from t = " + format_number(t_min) + " s",
                "time [s]", "F [m]", {{"infiltration_sim", "SPH porous flow (central band)", "line"},
                                         {"infiltration_exact", "Green-Ampt (falling head)", "line"},
                                         {"pond_depth", "pond depth h(t)", "line"}}},
               {"front_depth.png", "Wetting front depth (S >= 1/2)", "time [s]", "depth [m]",
                {{"front_sim", "SPH porous flow", "line"}, {"front_exact", "Green-Ampt F/dtheta", "line"}}}};
    return r;
  }

 private:
  /// Green-Ampt F at the sample times under the sampled pond depth (see the file comment).
  std::vector<double> falling_head_reference() const {
    std::vector<double> F(time_.size(), 0.0);
    if (time_.size() < 2) return F;
    F[1] = analytic::green_ampt_infiltration(K_, psi_ + pond_[0], dtheta_, time_[1] - time_[0]);
    constexpr int kSubsteps = 20;
    for (std::size_t k = 2; k < time_.size(); ++k) {
      const double t0 = time_[k - 1], dt = (time_[k] - t0) / kSubsteps;
      auto rate = [&](double t, double f) {
        const double h = pond_[k - 1] + (pond_[k] - pond_[k - 1]) * (t - t0) / (time_[k] - t0);
        return analytic::green_ampt_rate(K_, psi_, dtheta_, f, h);
      };
      double f = F[k - 1];
      for (int m = 0; m < kSubsteps; ++m) {
        const double t = t0 + m * dt;
        const double k1 = rate(t, f), k2 = rate(t + 0.5 * dt, f + 0.5 * dt * k1);
        const double k3 = rate(t + 0.5 * dt, f + 0.5 * dt * k2), k4 = rate(t + dt, f + dt * k3);
        f += dt * (k1 + 2.0 * k2 + 2.0 * k3 + k4) / 6.0;
      }
      F[k] = f;
    }
    return F;
  }
  double band_width() const {
    return std::round((band_hi_ - band_lo_) / dx_) * dx_;
  }
  void add(ObserverResult& r, const std::string& name, double value) const { add_metric(r, limits_, name, value); }

  double dx_, surface_, bottom_, sample_interval_, rho_, K_, dtheta_, psi_, band_lo_, band_hi_, tank_width_;
  double next_sample_ = 0.0, initial_ = 0.0;
  std::map<std::string, MetricLimit> limits_;
  WaterBalanceProbe<D> balance_;
  std::vector<double> time_, F_, front_, pond_;
};

}  // namespace

template <int D>
std::unique_ptr<Observer<D>> make_green_ampt_observer(const ObserverContext& ctx) {
  return std::make_unique<GreenAmptObserver<D>>(ctx);
}
template std::unique_ptr<Observer<2>> make_green_ampt_observer<2>(const ObserverContext&);
template std::unique_ptr<Observer<3>> make_green_ampt_observer<3>(const ObserverContext&);

}  // namespace sc
