// Basic types shared by the whole solver: fixed-size Eigen vectors and matrices templated on the
// spatial dimension D (2 or 3), and the particle phases.
#pragma once
#include <Eigen/Dense>
#include <cstdint>
#include <numbers>

namespace sc {

template <int D>
using Vec = Eigen::Matrix<double, D, 1>;
template <int D>
using Mat = Eigen::Matrix<double, D, D>;

/// What a particle is. Water and sand move; boundary particles are fixed wall samples.
enum class Phase : std::uint8_t { Water = 0, Sand = 1, Boundary = 2 };

inline constexpr double pi = std::numbers::pi;

}  // namespace sc
