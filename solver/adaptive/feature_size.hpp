// Extended local feature size (Adams et al. 2007 as recalled in docs/equations.md §4.6) on a regular
// background grid.
//
// What is computed, from a function f at the grid nodes that is negative inside the fluid:
//   1. surface samples y: the linear zero crossings of f along every grid edge;
//   2. the signed distance phi(x) = +-min_y |x - y| (negative inside) with the closest sample of
//      every node, by a Dijkstra-ordered closest-point propagation over the 3^D - 1 grid
//      neighbours (a vector-distance variant of fast marching: values are exact distances to the
//      carried sample, not upwind Eikonal solutions);
//   3. the medial axis: for every pair of axis-neighbour nodes (a, b) whose closest samples ca, cb
//      are more than `medial_jump` cells apart, whose directions a -> ca and b -> cb differ by more
//      than `medial_angle` (without it, every node near the centre of a disc, where the
//      closest-point map spreads fast but is continuous, would count) and whose bisector plane of
//      ca, cb crosses the segment ab: the crossing point. Both sides of the surface count (thin
//      sheets and thin gaps);
//   4. lfs(y) = distance from each surface sample to the nearest medial-axis point (a second
//      closest-point propagation seeded at the medial-axis points);
//   5. elfs(x) = min_y (min(lfs(y), lfs_max) + |x - y|) (a third propagation seeded with the
//      capped lfs on the surface), clamped to [elfs_min, elfs_max]. Without a medial axis (a
//      half-space) and without a cap, elfs = elfs_max.
//
// Verified (tests/test_adaptive.cpp): an analytic slab in 2-D and 3-D (exact to rounding) and a
// disc (lfs = R within half a cell). Not verified: other curved shapes, corners and wedges (a
// corner blunter than pi - medial_angle = 120 degrees gets no medial axis near its tip), the label
// propagation's known sub-cell misses of the true closest sample, noisy particle surfaces.
#pragma once
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/types.hpp"

namespace sc {

template <int D>
struct BackgroundGrid {
  Vec<D> origin = Vec<D>::Zero();  ///< position of node (0, ..., 0) [m]
  double dx = 1.0;                 ///< node spacing [m]
  std::array<int, D> n{};          ///< nodes per axis

  std::size_t size() const;
  std::size_t index(const std::array<int, D>& c) const;
  std::array<int, D> coords(std::size_t k) const;
  Vec<D> node(std::size_t k) const;
};

struct FeatureSizeParams {
  double medial_jump = 2.0;  ///< closest samples further apart than this many cells: medial axis
  double medial_angle = 1.0471975511965976;  ///< ... and directions to them apart by more [rad]
  double elfs_min = 0.0;     ///< clamp of elfs [m] (e.g. alpha * r_min)
  /// Also the reach of the computation: nodes further than elfs_max from the surface get
  /// distance ±infinity and elfs = elfs_max without being visited (their elfs is clamped anyway).
  double elfs_max = std::numeric_limits<double>::infinity();  ///< (runs: decision_band, adaptivity.hpp)
  /// Cap of lfs on the surface before it is extended inwards [m]. Infinite: Adams' elfs (a large
  /// smooth body may be coarse up to its surface). Finite: elfs = min_y (min(lfs(y), lfs_max) +
  /// |x - y|), so the surface stays fine and particles grow with depth (Persson's size function).
  double lfs_max = std::numeric_limits<double>::infinity();
  /// elfs is computed outside the region (f >= 0) only this far from the surface [m]; further out
  /// it is left at elfs_max. Runs sample elfs only at particles, each inside its own ball, so
  /// only the corners of their cells matter: within a cell diagonal outside (derive_adaptivity
  /// sets 2 cells). Where the water is a block, two thirds of the 3-D grid lie outside.
  double outside_reach = std::numeric_limits<double>::infinity();
};

template <int D>
struct FeatureSize {
  using VecArray = std::vector<Vec<D>, Eigen::aligned_allocator<Vec<D>>>;
  /// Signed distance to the surface at the nodes, < 0 inside [m]; +-infinity beyond
  /// min(elfs_max, lfs_max + 2 cells), the reach of the medial-axis search (medial points deeper
  /// than lfs_max cannot change the capped lfs).
  std::vector<double> distance;
  VecArray surface;              ///< surface samples y
  std::vector<double> lfs;       ///< local feature size at each surface sample [m]
  VecArray medial_axis;          ///< medial-axis points
  std::vector<double> elfs;      ///< extended local feature size at the nodes [m]
};

/// Feature size of the region f < 0 (f given at every node of the grid).
template <int D>
FeatureSize<D> feature_size(const BackgroundGrid<D>& grid, const std::vector<double>& f,
                            const FeatureSizeParams& params);

/// Multilinear interpolation of node values at x (clamped to the grid).
template <int D>
double sample_grid(const BackgroundGrid<D>& grid, const std::vector<double>& values,
                   const Vec<D>& x);

}  // namespace sc
