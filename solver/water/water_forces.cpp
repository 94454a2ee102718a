#include "water/water_forces.hpp"

#include <type_traits>

#include "water/pressure_force.hpp"
#include "water/surface_tension.hpp"
#include "water/viscosity_force.hpp"
#include "sph/neighbour_batch.hpp"

namespace sc {

namespace {

/// The reaction of the water's surface tension on a (moving) sand particle i: the pair forces of its water
/// neighbours, each the exact negative of the force add_water_forces gives that neighbour, so
/// water and sand together keep their momentum.
template <int D>
Vec<D> surface_tension_from_water(const ParticleSet<D>& ps, const NeighbourGrid<D>& nb, std::size_t i,
                                  double kappa_prime) {
  const kernel::Support<D> si(ps.h[i]);
  Vec<D> f = Vec<D>::Zero();
  for (const auto j : nb.of(i)) {
    if (ps.phase_of(j) != Phase::Water) continue;
    const Vec<D> d = ps.x[i] - ps.x[j];
    f += surface_tension_pair_force<D>(kappa_prime, ps.m[i], ps.m[j], d, d.norm(), si, ps.h[j]);
  }
  return f;
}

/// A batch's neighbour fields and the scalar factors of each pair force of WaterForceOn's
/// vectorised path (sph/neighbour_batch.hpp).
template <int D>
struct WaterPairTerms {
  static constexpr int K = NeighbourBatch<D>::kSize;
  alignas(32) double m[K], rho[K], p[K], viscous[K], cohesive[K];
  alignas(32) double gradient[K], pressure[K], viscosity[K], tension[K];
};

/// The water force on particle i, batch by batch: a batch whose supports all equal h_i computes
/// its pairs' scalar factors in one vectorised loop and then adds the forces in list order
/// (add_uniform_batch); any other batch takes the pairs one at a time, each kernel averaged over
/// h_i and h_j (add_general_batch). Both give the bits of the pair-by-pair sum.
template <int D>
class WaterForceOn {
 public:
  WaterForceOn(const ParticleSet<D>& ps, std::size_t i, const WaterParams& params, const MatArray<D>& correction,
               bool corrected, double kappa_prime)
      : ps_(ps), i_(i), params_(params), correction_(correction), corrected_(corrected), kappa_prime_(kappa_prime),
        Vi_(ps.volume(i)), Pi_(ps.p[i]), mi_(ps.m[i]), mu_(params.pair_viscosity(params.viscosity)), vi_(ps.v[i]),
        si_(ps.h[i]) {}

  void add(const NeighbourBatch<D>& b) {
    alignas(32) double h[NeighbourBatch<D>::kSize];
    b.gather(ps_.h.data(), h);
    if (b.all_equal(h, si_.h)) add_uniform_batch(b);
    else add_general_batch(b);
  }
  const Vec<D>& force() const { return f_; }

 private:
  /// One pair at a time, each kernel averaged over h_i and h_j (eqs 4, 5, surface tension).
  void add_general_batch(const NeighbourBatch<D>& b) {
    for (int k = 0; k < b.size; ++k) {
      const std::size_t j = b.j[k];
      if (j == i_) continue;
      Vec<D> d;
      for (int a = 0; a < D; ++a) d[a] = b.d[a][k];
      const double r = b.r[k], Vj = ps_.volume(j);
      const Vec<D> fp = pressure_pair_force<D>(Vi_, Vj, Pi_, ps_.p[j], d, r, si_, ps_.h[j], params_.mueller_half_pressure);
      f_ += corrected_ ? corrected_pair_term<D>(correction_[i_], correction_[j], fp) : fp;
      const bool boundary = ps_.phase_of(j) == Phase::Boundary;
      if (!boundary || ps_.rough[j])
        f_ += viscosity_pair_force<D>(mu_, Vi_, Vj, vi_, ps_.v[j], r, si_, ps_.h[j]);
      if (!boundary && kappa_prime_ != 0.0)
        f_ += surface_tension_pair_force<D>(kappa_prime_, mi_, ps_.m[j], d, r, si_, ps_.h[j]);
    }
  }

  /// The same terms for a batch of neighbours of support h_i: a factor left out is 0, and adding
  /// 0 to a sum that starts at +0 leaves its bits.
  void add_uniform_batch(const NeighbourBatch<D>& b) {
    WaterPairTerms<D> t;  // a local: the compiler sees that no store to it reaches the batch
    b.gather(ps_.m.data(), t.m);
    b.gather(ps_.rho.data(), t.rho);
    b.gather(ps_.p.data(), t.p);
    const bool tension = kappa_prime_ != 0.0;
    for (int k = 0; k < b.size; ++k) {  // which terms a pair has, as 1 or 0 (the loop below has no branch)
      const bool boundary = ps_.phase_of(b.j[k]) == Phase::Boundary;
      t.viscous[k] = !boundary || ps_.rough[b.j[k]] ? 1.0 : 0.0;
      t.cohesive[k] = !boundary && tension ? 1.0 : 0.0;
    }
    const kernel::Support<D> si = si_;
    const double Vi = Vi_, Pi = Pi_, mi = mi_, mu = mu_, kappa = kappa_prime_;
    // Müller's half as a constant of the loop's code (a flag read in the loop stops it vectorising).
    const auto factors = [&](auto half) {
      for (int k = 0; k < b.size; ++k) {
        const double r = b.r[k], Vj = t.m[k] / t.rho[k];
        t.gradient[k] = kernel::spiky_gradient_factor<D>(r, si);
        t.pressure[k] = pressure_pair_coefficient(Vi, Vj, Pi, t.p[k], half());
        const double viscosity = viscosity_pair_coefficient(mu, Vi, Vj, kernel::viscosity_laplacian<D>(r, si));
        t.viscosity[k] = t.viscous[k] != 0.0 ? viscosity : 0.0;
        const double cohesion = surface_tension_pair_coefficient(kappa, mi, t.m[k], kernel::poly6<D>(r, si));
        t.tension[k] = t.cohesive[k] != 0.0 ? cohesion : 0.0;
      }
    };
    if (params_.mueller_half_pressure) factors(std::true_type{});
    else factors(std::false_type{});
    // Summed in a local: a store to the member f_ could alias any double the loop reads, so the
    // compiler would store it and reload L_i after every pair.
    Vec<D> f = f_;
    const Mat<D> Li = corrected_ ? correction_[i_] : Mat<D>::Identity();
    for (int k = 0; k < b.size; ++k) {
      const std::size_t j = b.j[k];
      if (j == i_) continue;
      Vec<D> d;
      for (int a = 0; a < D; ++a) d[a] = b.d[a][k];
      const double r = b.r[k];
      const Vec<D> grad = r >= si.h || r <= 0.0 ? Vec<D>::Zero() : Vec<D>(t.gradient[k] * d);
      const Vec<D> fp = t.pressure[k] * grad;
      f += corrected_ ? corrected_pair_term<D>(Li, correction_[j], fp) : fp;
      f += t.viscosity[k] * (ps_.v[j] - vi_);
      f += t.tension[k] * d;
    }
    f_ = f;
  }

  const ParticleSet<D>& ps_;
  const std::size_t i_;
  const WaterParams& params_;
  const MatArray<D>& correction_;
  const bool corrected_;
  const double kappa_prime_, Vi_, Pi_, mi_, mu_;  // mu_: the pair viscosity of eq 5
  const Vec<D> vi_;
  const kernel::Support<D> si_;
  Vec<D> f_ = Vec<D>::Zero();
};

}  // namespace

template <int D>
void add_water_forces(ParticleSet<D>& ps, const NeighbourGrid<D>& nb, const WaterParams& params,
                      const MatArray<D>& correction) {
  const bool corrected = params.gradient_correction && correction.size() == ps.size();
  const auto n = static_cast<std::int64_t>(ps.size());
  const double kappa_prime = params.surface_tension / params.reference_mass;
  // Dynamic: the work per particle varies (walls, free surface) and moving particles are stored first.
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t i = 0; i < n; ++i) {
    if (ps.phase_of(i) == Phase::Sand && kappa_prime != 0.0)
      ps.force[i] += surface_tension_from_water(ps, nb, i, kappa_prime);
    if (ps.phase_of(i) != Phase::Water) continue;
    WaterForceOn<D> on(ps, i, params, correction, corrected, kappa_prime);
    for_each_batch<D>(nb.of(i), ps.x[i], ps.x.data(), [&](const NeighbourBatch<D>& b) { on.add(b); });
    ps.force[i] += on.force();
  }
}

template void add_water_forces<2>(ParticleSet<2>&, const NeighbourGrid<2>&, const WaterParams&, const MatArray<2>&);
template void add_water_forces<3>(ParticleSet<3>&, const NeighbourGrid<3>&, const WaterParams&, const MatArray<3>&);

}  // namespace sc
