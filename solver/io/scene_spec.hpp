// The scene of a case as plain data: its lattice blocks and its box tank, parsed into enums at the
// boundary (case/case_file.cpp). Scene building (scene/) and wall collision (boundary/) read only
// this, not the physics parameters of the whole case.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "core/types.hpp"

namespace sc {

/// What a block of a case is filled with.
enum class BlockFill { Water, Sand, PorousBed };

/// A rectangular block of particles on a lattice at the case spacing.
struct BlockSpec {
  BlockFill fill = BlockFill::Water;
  std::vector<double> min, max;  ///< corners [m]
  /// Initial rigid spin ω [rad/s] of the block about its centre of mass, v = ω × (x − x_cm): three
  /// components in 3-D, one (about the normal of the plane) in 2-D; empty: the block starts at rest.
  std::vector<double> angular_velocity;
  /// The phase of its particles: a porous bed is a fixed skeleton of boundary-phase particles.
  Phase phase() const {
    return fill == BlockFill::Sand ? Phase::Sand : (fill == BlockFill::Water ? Phase::Water : Phase::Boundary);
  }
};

/// How a side of the tank treats the fluid: a rough wall, a smooth wall, or no wall.
enum class WallRule { NoSlip, Slip, Open };

/// A container whose walls are layers of boundary particles outside [min, max]. In the case file
/// its sides are named "x-", "x+", "y-", "y+" (and "z-", "z+" in 3-D), each "no_slip", "slip" or
/// "open".
struct TankSpec {
  std::vector<double> min, max;
  /// The rule of each side, indexed by side_index(axis, outward).
  std::array<WallRule, 6> rules{WallRule::Open, WallRule::Open, WallRule::Open,
                                WallRule::Open, WallRule::Open, WallRule::Open};
  /// Closed sides also stop moving particles by collision (boundary/wall_collision.hpp), behind the
  /// wall particles: for scenes whose splashes are too fast for the wall particles alone.
  bool collision = false;

  /// Side of axis d facing outward = -1 (at min) or +1 (at max).
  static int side_index(int d, int outward) { return 2 * d + (outward > 0 ? 1 : 0); }
  WallRule rule(int d, int outward) const { return rules[side_index(d, outward)]; }
  bool closed(int d, int outward) const { return rule(d, outward) != WallRule::Open; }
  /// The case-file name of a side, e.g. "y-".
  static std::string side_name(int d, int outward) { return std::string(1, "xyz"[d]) + (outward > 0 ? "+" : "-"); }
};

}  // namespace sc
