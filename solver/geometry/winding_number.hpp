// Generalised winding number of a triangle mesh (Jacobson, Kavan & Sorkine-Hornung 2013), evaluated
// hierarchically (Barill et al. 2018): w(q) = Σ_t Ω_t(q) / 4π, with Ω_t the signed solid angle of
// triangle t seen from q. w is 1 inside and 0 outside a closed, outward-oriented mesh, and degrades
// gracefully (fractional values) near flaws such as self-intersections or small gaps.
#pragma once
#include <vector>

#include "geometry/triangle_mesh.hpp"

namespace sc {

class WindingNumber {
 public:
  explicit WindingNumber(const TriangleMesh& mesh);

  /// The winding number at q. Clusters of triangles farther than `far_ratio` times their radius
  /// are summed by their dipole term Σ a_t n_t; nearer ones exactly (Van Oosterom & Strackee 1983).
  double operator()(const Vec<3>& q) const;
  /// Inside test: |w| > 1/2 (accepts inward-oriented meshes too).
  bool inside(const Vec<3>& q) const;

 private:
  struct Node {
    Vec<3> centre;       // area-weighted centroid of its triangles
    Vec<3> area_normal;  // Σ_t a_t n_t (half the cross products)
    double radius = 0.0; // all its vertices lie within this distance of centre
    std::uint32_t first = 0, count = 0;  // triangle range (leaves)
    std::int32_t left = -1, right = -1;  // children (inner nodes)
  };
  std::int32_t build(std::uint32_t first, std::uint32_t count);
  double solid_angle(std::uint32_t t, const Vec<3>& q) const;

  const TriangleMesh& mesh_;
  std::vector<std::uint32_t> order_;  // triangle indices, grouped by node
  std::vector<Node> nodes_;
  static constexpr double far_ratio = 3.0;
};

/// Points of the lattice min + (k + 1/2) dx over the mesh's bounding box that lie inside it.
std::vector<Vec<3>, Eigen::aligned_allocator<Vec<3>>> sample_inside(const TriangleMesh& mesh, double dx);

}  // namespace sc
