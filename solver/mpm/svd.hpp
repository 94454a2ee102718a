// The singular value decomposition F = U Σ Vᵀ of a deformation gradient with det F > 0, as the
// return mapping needs it (Klár et al. 2016 work on the principal stretches Σ): V and Σ² from the
// symmetric eigenproblem of FᵀF, U = F V Σ⁻¹, so U and V are rotations or reflections together and
// U Σ Vᵀ reproduces F.
#pragma once
#include <Eigen/Eigenvalues>

#include "core/types.hpp"

namespace sc::mpm {

template <int D>
struct Svd {
  Mat<D> U, V;
  Vec<D> sigma;
};

template <int D>
Svd<D> svd(const Mat<D>& F) {
  const Eigen::SelfAdjointEigenSolver<Mat<D>> es(F.transpose() * F);
  Svd<D> s;
  s.V = es.eigenvectors();
  s.sigma = es.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  s.U = F * s.V * s.sigma.cwiseInverse().asDiagonal();
  return s;
}

}  // namespace sc::mpm
