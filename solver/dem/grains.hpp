// DEM grains: discs (D = 2) and spheres (D = 3) as a structure of arrays, with the water each one
// holds (Rungjiratananon et al. 2008, seed 003). A grain moves its dry mass plus the water it holds,
// so absorbing a water particle conserves momentum (solver/dem/water_coupling.hpp).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "core/types.hpp"
#include "dem/dem_params.hpp"

namespace sc::dem {

/// Angular velocity or torque: a scalar about z in 2-D, a vector in 3-D.
template <int D>
using Spin = Eigen::Matrix<double, D == 2 ? 1 : 3, 1>;

/// ω × r: the velocity of a point at offset r of a body spinning at ω.
template <int D>
inline Vec<D> spin_cross(const Spin<D>& w, const Vec<D>& r) {
  if constexpr (D == 2) return Vec<D>(-w[0] * r[1], w[0] * r[0]);
  else return w.cross(r);
}
/// r × F: the torque of force F applied at offset r.
template <int D>
inline Spin<D> moment(const Vec<D>& r, const Vec<D>& f) {
  if constexpr (D == 2) return Spin<D>(r[0] * f[1] - r[1] * f[0]);
  else return r.cross(f);
}

/// A fixed contact plane (a tank wall): a point on it, its unit normal into the domain, and whether
/// it is rough (Params::wall_friction) or smooth (no tangential force).
template <int D>
struct Plane {
  Vec<D> point;
  Vec<D> normal;
  bool rough = true;
};

/// What a contact remembers from step to step, kept by grain i (Grains::springs, Grains::wall_springs):
/// the tangential spring's stretch ξ and the rolling spring's twist ψ, both from i's side (the other
/// grain's are their exact negatives).
template <int D>
struct Spring {
  std::uint32_t other = 0;          ///< the other grain, or wall_key(w) for wall w
  Vec<D> slip = Vec<D>::Zero();     ///< ξ [m]
  Spin<D> roll = Spin<D>::Zero();   ///< ψ [rad]
};

/// The contacts the grains kept of the last step, each by one grain and from its side, in one array:
/// grain i's are the first count(i) of its `capacity()` slots. One array in grain order, not a vector per grain, so the
/// contact gather reads them as it walks the grains. A grain that keeps more contacts than the
/// capacity is told so by keep(); grow() then makes room for all (the same contacts, any threads).
template <int D>
class ContactHistory {
 public:
  std::size_t size() const { return count_.size(); }
  std::size_t capacity() const { return capacity_; }
  /// Grain i's contacts of the last step.
  std::span<const Spring<D>> of(std::size_t i) const { return {slots_.data() + i * capacity_, count_[i]}; }
  /// Keeps `kept` as grain i's contacts; false, keeping none, when they exceed the capacity.
  bool keep(std::size_t i, std::span<const Spring<D>> kept) {
    if (kept.size() > capacity_) {
      count_[i] = 0;
      return false;
    }
    std::copy(kept.begin(), kept.end(), slots_.begin() + static_cast<std::ptrdiff_t>(i * capacity_));
    count_[i] = static_cast<std::uint32_t>(kept.size());
    return true;
  }
  /// Forgets grain i's contacts.
  void clear(std::size_t i) { count_[i] = 0; }
  /// Appends a grain without contacts.
  void add_grain() {
    count_.push_back(0);
    slots_.resize(count_.size() * capacity_);
  }
  /// Makes room for `needed` contacts per grain, keeping every grain's.
  void grow(std::size_t needed) {
    if (needed <= capacity_) return;
    std::vector<Spring<D>, Eigen::aligned_allocator<Spring<D>>> wider(size() * needed);
    for (std::size_t i = 0; i < size(); ++i) std::ranges::copy(of(i), wider.begin() + static_cast<std::ptrdiff_t>(i * needed));
    slots_ = std::move(wider);
    capacity_ = needed;
  }

 private:
  std::vector<Spring<D>, Eigen::aligned_allocator<Spring<D>>> slots_;
  std::vector<std::uint32_t> count_;
  std::size_t capacity_ = 8;
};

/// The key of wall w in Spring::other (grain indices count up from 0, walls down from the top).
inline std::uint32_t wall_key(std::size_t w) { return 0xffffffffu - static_cast<std::uint32_t>(w); }

template <int D>
struct Grains {
  using VecArray = std::vector<Vec<D>, Eigen::aligned_allocator<Vec<D>>>;
  using SpinArray = std::vector<Spin<D>, Eigen::aligned_allocator<Spin<D>>>;
  VecArray x, v, force;           ///< position [m], velocity [m/s], force of the step [N]
  SpinArray omega, torque;        ///< angular velocity [rad/s], torque of the step [N m]
  std::vector<double> radius;     ///< dry radius R [m]
  std::vector<double> dry_mass;   ///< [kg] (2-D: per metre of depth)
  std::vector<double> water;      ///< water held [kg]
  ContactHistory<D> springs;      ///< contacts between grains of the last step, each kept by its lower grain
  ContactHistory<D> wall_springs; ///< each grain's contacts with walls of the last step

  std::size_t size() const { return x.size(); }
  /// Appends a grain at rest; its dry mass is density times its volume.
  std::size_t add(const Vec<D>& at, double r, double density) {
    x.push_back(at); v.push_back(Vec<D>::Zero()); force.push_back(Vec<D>::Zero());
    omega.push_back(Spin<D>::Zero()); torque.push_back(Spin<D>::Zero());
    radius.push_back(r); dry_mass.push_back(density * volume_of(r)); water.push_back(0.0);
    springs.add_grain();
    wall_springs.add_grain();
    return x.size() - 1;
  }
  static double volume_of(double r) { return D == 3 ? 4.0 / 3.0 * pi * r * r * r : pi * r * r; }
  double volume(std::size_t i) const { return volume_of(radius[i]); }
  double mass(std::size_t i) const { return dry_mass[i] + water[i]; }
  /// Moment of inertia of a uniform sphere (2/5 m R²) or disc (1/2 m R²).
  double inertia(std::size_t i) const { return (D == 3 ? 0.4 : 0.5) * mass(i) * radius[i] * radius[i]; }
  /// Water held at saturation 1 [kg].
  double capacity(std::size_t i, const Params& p) const { return p.capacity_fraction * p.water_density * volume(i); }
  /// The paper's wetness w: water held over capacity (0 dry, w_f the over-wet threshold). A dry
  /// grain's is 0 without the division (the contact laws ask for it several times per pair).
  double saturation(std::size_t i, const Params& p) const {
    return water[i] == 0.0 ? 0.0 : water[i] / capacity(i, p);
  }
  /// Radius shrinking with wetness, r = R − k_r w, bounded below by a fraction of R
  /// [Rungjiratananon 2008: wet radius].
  double wet_radius(std::size_t i, const Params& p) const {
    return std::max(radius[i] - p.radius_shrink * saturation(i, p), p.min_radius_fraction * radius[i]);
  }
};

/// Stable step of the explicit contact integration: a tenth of √(m/k) of the lightest grain,
/// i.e. about 1/31 of an undamped contact's duration π√(m/k) (half its natural period 2π√(m/k)).
template <int D>
double stable_step(const Grains<D>& g, const Params& p) {
  double m = INFINITY;
  for (std::size_t i = 0; i < g.size(); ++i) m = std::min(m, g.mass(i));
  return 0.1 * std::sqrt(m / p.stiffness);
}

/// Dashpot k_d giving restitution e for effective mass m_eff and spring k (linear spring-dashpot:
/// e = exp(−π ζ/√(1−ζ²)), ζ = k_d/(2√(k m_eff)), inverted).
inline double damping_for_restitution(double e, double k, double m_eff) {
  const double l = std::log(e);
  return -2.0 * l * std::sqrt(k * m_eff / (pi * pi + l * l));
}

}  // namespace sc::dem
