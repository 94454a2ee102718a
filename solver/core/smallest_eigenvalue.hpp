// The smallest eigenvalue of a symmetric 2x2 or 3x3 matrix in closed form (no iteration), for
// the blend weight of the kernel-gradient correction (sph/gradient_correction.hpp).
#pragma once
#include <algorithm>
#include <cmath>

#include "core/types.hpp"

namespace sc {

/// The smallest eigenvalue of a symmetric 2x2 matrix: mean of the diagonal minus the radius of
/// Mohr's circle, (a + c)/2 − √(((a − c)/2)² + b²). Absolute error a few ulps of |S|.
inline double smallest_eigenvalue(const Mat<2>& S) {
  const double mean = 0.5 * (S(0, 0) + S(1, 1));
  const double half_gap = 0.5 * (S(0, 0) - S(1, 1));
  return mean - std::sqrt(half_gap * half_gap + S(0, 1) * S(0, 1));
}

/// The smallest eigenvalue of a symmetric 3x3 matrix by the trigonometric solution of its
/// characteristic cubic (Smith 1961): with q = tr S/3, B = (S − qI)/p and p² = tr((S − qI)²)/6, the
/// eigenvalues are q + 2p cos(φ + 2πk/3), φ = acos(det B/2)/3, the smallest at k = 1. Only the upper
/// triangle is read. Where the two smallest eigenvalues nearly coincide (det B/2 → 1) acos
/// amplifies the rounding of det B up to ~√ε p, so there (1 − det B/2 < kNearDouble) the iterative
/// solver (Eigen's QR) is used instead; elsewhere the error is below 1e-12 |S|. Tested against the
/// solver on random and near-degenerate matrices (test
/// water/smallest_eigenvalue_closed_form_matches_iterative_solver).
inline double smallest_eigenvalue(const Mat<3>& S) {
  constexpr double kNearDouble = 1e-6;
  const double q = (S(0, 0) + S(1, 1) + S(2, 2)) / 3.0;
  const double b00 = S(0, 0) - q, b11 = S(1, 1) - q, b22 = S(2, 2) - q;
  const double b01 = S(0, 1), b02 = S(0, 2), b12 = S(1, 2);
  const double p2 = (b00 * b00 + b11 * b11 + b22 * b22 + 2.0 * (b01 * b01 + b02 * b02 + b12 * b12)) / 6.0;
  if (p2 == 0.0) return q;  // S = qI
  const double p = std::sqrt(p2);
  const double det = b00 * (b11 * b22 - b12 * b12) - b01 * (b01 * b22 - b12 * b02) + b02 * (b01 * b12 - b11 * b02);
  const double half_det = std::clamp(det / (2.0 * p2 * p), -1.0, 1.0);
  if (1.0 - half_det < kNearDouble) {
    const Mat<3> full = S.selfadjointView<Eigen::Upper>();
    return Eigen::SelfAdjointEigenSolver<Mat<3>>(full, Eigen::EigenvaluesOnly).eigenvalues()[0];
  }
  return q + 2.0 * p * std::cos(std::acos(half_det) / 3.0 + 2.0 * pi / 3.0);
}

}  // namespace sc
