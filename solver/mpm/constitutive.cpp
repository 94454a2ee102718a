#include "mpm/constitutive.hpp"

#include "mpm/svd.hpp"

namespace sc::mpm {

double cone_slope(int dim, double friction_angle_deg) {
  const double s = std::sin(friction_angle_deg * pi / 180.0);
  return dim == 2 ? s / std::sqrt(2.0) : std::sqrt(2.0 / 3.0) * 2.0 * s / (3.0 - s);
}

SandModel SandModel::from(int dim, double youngs, double poisson, double friction_angle_deg, bool volume_correction) {
  SandModel m;
  m.mu = youngs / (2.0 * (1.0 + poisson));
  m.lambda = youngs * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
  m.alpha = cone_slope(dim, friction_angle_deg);
  m.cot_phi = 1.0 / std::tan(friction_angle_deg * pi / 180.0);
  m.volume_correction = volume_correction;
  return m;
}

template <int D>
Mat<D> hencky_kirchhoff(const Mat<D>& U, const Vec<D>& eps, const SandModel& m) {
  const Vec<D> t = (2.0 * m.mu * eps.array() + m.lambda * eps.sum()).matrix();
  return U * t.asDiagonal() * U.transpose();
}

template <int D>
Mat<D> hencky_kirchhoff(const Mat<D>& Fe, const SandModel& m) {
  const Svd<D> s = svd<D>(Fe);
  return hencky_kirchhoff<D>(s.U, Vec<D>(s.sigma.array().log().matrix()), m);
}

template <int D>
Projection<D> project_drucker_prager(const Vec<D>& eps, double cohesion, double volume_correction, const SandModel& m) {
  const double apex = cohesion * m.cot_phi / (2.0 * m.mu + D * m.lambda);
  const Vec<D> trial = (eps.array() + (m.volume_correction ? volume_correction / D : 0.0)).matrix();
  const Vec<D> e = (trial.array() - apex).matrix();  // relative to the apex
  const double tr = e.sum();
  const Vec<D> dev = (e.array() - tr / D).matrix();
  const double dev_norm = dev.norm();
  Vec<D> out = trial;
  if (tr >= 0.0) {
    out.setConstant(apex);  // case II: expansion, to the apex
  } else {
    const double dgamma = dev_norm + m.alpha * (D * m.lambda + 2.0 * m.mu) / (2.0 * m.mu) * tr;
    if (dgamma > 0.0) out = (e - dgamma / dev_norm * dev).array() + apex;  // case III: onto the cone
  }
  Projection<D> p{out, 0.0};
  if (m.volume_correction) p.volume_correction = volume_correction + eps.sum() - out.sum();
  return p;
}

template Mat<2> hencky_kirchhoff<2>(const Mat<2>&, const SandModel&);
template Mat<3> hencky_kirchhoff<3>(const Mat<3>&, const SandModel&);
template Mat<2> hencky_kirchhoff<2>(const Mat<2>&, const Vec<2>&, const SandModel&);
template Mat<3> hencky_kirchhoff<3>(const Mat<3>&, const Vec<3>&, const SandModel&);
template Projection<2> project_drucker_prager<2>(const Vec<2>&, double, double, const SandModel&);
template Projection<3> project_drucker_prager<3>(const Vec<3>&, double, double, const SandModel&);

}  // namespace sc::mpm
