// Conjugate gradients for sparse symmetric positive definite systems, with every sum in an order
// that does not depend on the instruction set the solver is built for (docs/performance.md, "Build
// flags and vectorised pair loops"), so that an SSE and an AVX2 build give the same bits.
#pragma once
#include <Eigen/SparseCore>

#include <algorithm>
#include <limits>

namespace sc {

/// Σ_k a_k b_k in one order for every build: while four terms remain they go to four partial sums
/// (term k to sum k mod 4), which are then added as (s0 + s2) and (s1 + s3); a remaining pair of
/// terms is added to these two, the two are added, and a last odd term is added to the result
/// (fewer than four terms: left to right). Eigen's dot products keep one partial sum per lane of
/// its SIMD packets, so their order, and the last bits of a result, follow the packet width (two
/// doubles with SSE, four with AVX2); this is the order of its SSE reduction, so the solves keep
/// the bits of the SSE builds. The four partial sums are independent: a compiler may hold them in
/// one vector register of any width without changing a bit.
inline double ordered_dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const Eigen::Index n = a.size();
  if (n < 4) {
    double sum = n > 0 ? a[0] * b[0] : 0.0;
    for (Eigen::Index k = 1; k < n; ++k) sum += a[k] * b[k];
    return sum;
  }
  double s[4];
  for (int l = 0; l < 4; ++l) s[l] = a[l] * b[l];
  Eigen::Index k = 4;
  for (; k + 4 <= n; k += 4)
    for (int l = 0; l < 4; ++l) s[l] += a[k + l] * b[k + l];
  double even = s[0] + s[2], odd = s[1] + s[3];
  if (k + 2 <= n) {
    even += a[k] * b[k];
    odd += a[k + 1] * b[k + 1];
    k += 2;
  }
  double sum = even + odd;
  if (k < n) sum += a[k] * b[k];
  return sum;
}

/// Solves A x = b for a symmetric positive definite A by conjugate gradients with the Jacobi
/// preconditioner (Hestenes & Stiefel 1952), from the guess in x, until the squared residual is
/// below tol² |b|² or after 2n iterations; returns the iterations taken. Step for step Eigen's
/// ConjugateGradient<SparseMatrix, Lower | Upper>, with ordered_dot for its dot products: its
/// other operations are element by element or, in the product with A (taken through the
/// row-major view A^T, as Eigen does), a sum along each row in storage order, so they give the same
/// bits on every instruction set.
inline Eigen::Index conjugate_gradient(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& b,
                                       Eigen::VectorXd& x, double tol) {
  const auto rows = A.transpose();
  const Eigen::VectorXd inverse_diagonal = A.diagonal().cwiseInverse();
  Eigen::VectorXd residual = b - rows * x;
  const double b_norm2 = ordered_dot(b, b);
  if (b_norm2 == 0.0) {
    x.setZero();
    return 0;
  }
  const double threshold = std::max(tol * tol * b_norm2, std::numeric_limits<double>::min());
  if (ordered_dot(residual, residual) < threshold) return 0;
  Eigen::VectorXd p = inverse_diagonal.cwiseProduct(residual), z(A.cols()), Ap(A.cols());
  double rz = ordered_dot(residual, p);
  const Eigen::Index max_iterations = 2 * A.cols();
  Eigen::Index i = 0;
  while (i < max_iterations) {
    Ap.noalias() = rows * p;
    const double alpha = rz / ordered_dot(p, Ap);
    x += alpha * p;
    residual -= alpha * Ap;
    if (ordered_dot(residual, residual) < threshold) break;
    z = inverse_diagonal.cwiseProduct(residual);
    const double rz_old = rz;
    rz = ordered_dot(residual, z);
    p = z + (rz / rz_old) * p;
    ++i;
  }
  return i;
}

}  // namespace sc
