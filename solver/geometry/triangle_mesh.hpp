// Closed triangle meshes (Wavefront OBJ): loading, checks, and placement in a scene.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "core/types.hpp"
#include "io/mesh_spec.hpp"

namespace sc {

struct TriangleMesh {
  std::vector<Vec<3>, Eigen::aligned_allocator<Vec<3>>> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;

  Vec<3> bbox_min() const;
  Vec<3> bbox_max() const;
  /// Signed volume by the divergence theorem (positive when the normals point outward).
  double signed_volume() const;
};

/// Loads the triangles of an OBJ file (tinyobjloader, polygons triangulated). Throws InputError
/// naming the file when it is missing, unreadable, holds no triangle, or has a non-finite vertex.
TriangleMesh load_obj(const std::string& path);

/// Edge topology of a mesh: edges used by one triangle only (they border a hole) and edges shared
/// by more than two triangles (non-manifold).
struct EdgeReport {
  std::size_t edges = 0, boundary = 0, non_manifold = 0;
};
EdgeReport edge_report(const TriangleMesh& mesh);

/// Throws InputError naming `path` unless every edge is shared by exactly two triangles: a mesh
/// with holes has no well-defined inside, so it is refused rather than filled by a guess.
void require_closed(const TriangleMesh& mesh, const std::string& path);

/// Places a mesh as a case's MeshPlacement says (io/mesh_spec.hpp).
TriangleMesh place_mesh(TriangleMesh mesh, const MeshPlacement& placement);

}  // namespace sc
