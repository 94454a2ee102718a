// Observer "darcy_column": constant-head permeameter (docs/references.md §4) in the porous-flow model.
// A saturated fixed porous column (bottom z_b, top z_t, length L) is fed by a pond on top and
// drains into air below (seepage face). The outflow is all water below the column (water
// particles and emission stores); its rate over [fit_start, end], per unit width, is the Darcy
// flux q, compared with K_h (L + h_p)/L, K_h = k ρ^f g / μ, with h_p the pond depth averaged
// over the same window. The pond drains slowly (the head changes by a few % per second) and the
// pressure of a rigid skeleton follows it at once (solver/porous/rigid_pore_pressure.hpp), so
// the mean head gives the mean flux. Pond depth and outflow: water volumes as the lattice holds
// them, each full-size water particle one spacing^D (lattice_water_volume; the pressure it
// exerts, its mass being the lattice mass). The pore-water pressure P^p − P^c in the central band
// at the end is compared with the linear profile from ρ g h_p at the top to 0 at the bottom (relative RMS over ρ g (L + h_p)).
// Metrics: flux_rel_error, pressure_profile_error, water_balance_rel_error, saturation_violation;
// informational: flux [m/s], ponding_depth [m] (window mean).
// Pond depth and outflow count water in full water particles (full_water_mass: SPH's probe, or the
// lattice mass of MPM, whose held bed reports its sand as a fixed porous phase with the pore pressure).
#include <cctype>

#include "observer.hpp"
#include "porous_probe.hpp"

namespace sc {

namespace {

template <int D>
class DarcyColumnObserver : public Observer<D> {
 public:
  explicit DarcyColumnObserver(const ObserverContext& ctx) : dx_(ctx.spacing) {
    JsonObject o = validation_block(ctx);
    if (!ctx.spec.porous || !ctx.spec.tank) o.fail("observer", "darcy_column needs a \"porous\" section and a tank");
    bottom_ = o.number("column_bottom");
    top_ = o.number("column_top");
    fit_start_ = o.non_negative("fit_start", 0.0);
    limits_ = read_metric_limits(o);
    o.finish();
    const PorousParams& p = *ctx.spec.porous;
    rho_ = p.fluid_density;
    g_ = std::abs(ctx.spec.gravity[D - 1]);
    K_ = p.permeability * rho_ * g_ / p.fluid_viscosity;
    width_ = ctx.spec.tank->max[0] - ctx.spec.tank->min[0];
    for (int d = 1; d < D - 1; ++d) width_ *= ctx.spec.tank->max[d] - ctx.spec.tank->min[d];
    band_lo_ = ctx.spec.tank->min[0] + 0.25 * (ctx.spec.tank->max[0] - ctx.spec.tank->min[0]);
    band_hi_ = ctx.spec.tank->max[0] - 0.25 * (ctx.spec.tank->max[0] - ctx.spec.tank->min[0]);
    balance_ = WaterBalanceProbe<D>(p.fluid_density);
  }

  void sample(const Method<D>& run) override {
    balance_.sample(run);
    const ParticleView<D> ps = run.particles();
    const double water_mass = full_water_mass(run, rho_, dx_);
    double out = 0.0, pond = 0.0;
    for (std::size_t i = 0; i < ps.size(); ++i) {
      if (ps.phase_of(i) == Phase::Water && ps.x[i][D - 1] < bottom_) out += ps.m[i];
      if (ps.phase_of(i) == Phase::Water && ps.x[i][D - 1] > top_) pond += ps.m[i];
      if (!ps.leaving_water.empty() && ps.porosity[i] > 0.0) out += ps.leaving_water[i];
    }
    time_.push_back(run.time());
    outflow_.push_back(lattice_water_volume<D>(out, water_mass, dx_) / width_);
    pond_.push_back(lattice_water_volume<D>(pond, water_mass, dx_) / width_);
  }

  ObserverResult finish(const Method<D>& run) override {
    ObserverResult r;
    std::vector<double> t, y;
    double pond_sum = 0.0;
    for (std::size_t k = 0; k < time_.size(); ++k)
      if (time_[k] >= fit_start_) { t.push_back(time_[k]); y.push_back(outflow_[k]); pond_sum += pond_[k]; }
    const double L = top_ - bottom_;
    const double q = t.size() > 2 ? fitted_slope(t, y) : NAN;
    const double hp = t.empty() ? NAN : pond_sum / t.size();
    const double q_ref = K_ * (L + hp) / L;
    add(r, "flux", q);
    add(r, "ponding_depth", hp);
    add(r, "flux_rel_error", std::abs(q - q_ref) / q_ref);
    add(r, "pressure_profile_error", pressure_profile(run.particles(), pond_.empty() ? 0.0 : pond_.back(), r));
    add(r, "water_balance_rel_error", balance_.relative_error());
    add(r, "saturation_violation", balance_.saturation_violation());
    std::vector<double> ref(time_.size(), outflow_.empty() ? 0.0 : outflow_.front());
    for (std::size_t k = 1; k < time_.size(); ++k)  // ∫ K (L + h_p(t))/L dt with the measured pond
      ref[k] = ref[k - 1] + K_ * (L + 0.5 * (pond_[k] + pond_[k - 1])) / L * (time_[k] - time_[k - 1]);
    std::string who(run.name());  // the method, as the plots name it
    for (char& c : who) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    r.series.push_back({"outflow_sim", "time [s]", "outflow per unit width [m]", time_, outflow_});
    r.series.push_back({"outflow_exact", "time [s]", "outflow per unit width [m]", time_, ref});
    r.plots.push_back({"outflow.png", "Permeameter outflow (slope = Darcy flux)", "time [s]", "outflow [m]",
                       {{"outflow_sim", who + " porous flow", "line"}, {"outflow_exact", "Darcy: integral of K (L + hp(t))/L", "line"}}});
    r.plots.push_back({"pore_pressure.png", "Pore-water pressure P^p - P^c", "pressure [Pa]", "height [m]",
                       {{"pressure_sim", who + " (row mean, central band)", "markers"}, {"pressure_exact", "Darcy", "line"}}});
    return r;
  }

 private:
  double pressure_profile(const ParticleView<D>& ps, double hp, ObserverResult& r) const {
    const auto rows = static_cast<std::size_t>(std::lround((top_ - bottom_) / dx_));
    const std::vector<double> mean = row_means(ps, ps.pore_water_pressure, band_lo_, band_hi_, bottom_, dx_, rows);
    Series sim_s{"pressure_sim", "pressure [Pa]", "height [m]", {}, {}}, ref_s{"pressure_exact", "pressure [Pa]", "height [m]", {}, {}};
    double err2 = 0.0;
    const double scale = rho_ * g_ * (top_ - bottom_ + hp);
    for (std::size_t k = 0; k < rows; ++k) {
      const double z = bottom_ + (k + 0.5) * dx_;
      const double ref = rho_ * g_ * hp * (z - bottom_) / (top_ - bottom_);
      sim_s.x.push_back(mean[k]); sim_s.y.push_back(z);
      ref_s.x.push_back(ref); ref_s.y.push_back(z);
      err2 += (mean[k] - ref) * (mean[k] - ref);
    }
    r.series.push_back(sim_s);
    r.series.push_back(ref_s);
    return std::sqrt(err2 / rows) / scale;
  }
  void add(ObserverResult& r, const std::string& name, double value) const { add_metric(r, limits_, name, value); }

  double dx_, bottom_, top_, fit_start_, rho_, g_, K_, width_, band_lo_, band_hi_;
  std::map<std::string, MetricLimit> limits_;
  WaterBalanceProbe<D> balance_;
  std::vector<double> time_, outflow_, pond_;
};

}  // namespace

template <int D>
std::unique_ptr<Observer<D>> make_darcy_column_observer(const ObserverContext& ctx) {
  return std::make_unique<DarcyColumnObserver<D>>(ctx);
}
template std::unique_ptr<Observer<2>> make_darcy_column_observer<2>(const ObserverContext&);
template std::unique_ptr<Observer<3>> make_darcy_column_observer<3>(const ObserverContext&);

}  // namespace sc
