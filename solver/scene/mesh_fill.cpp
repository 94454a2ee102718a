#include "scene/mesh_fill.hpp"

#include "geometry/winding_number.hpp"

namespace sc {

namespace {

void check_fits(const CaseSpec& spec, const MeshSpec& mesh, const TriangleMesh& placed) {
  const Vec<3> lo = placed.bbox_min(), hi = placed.bbox_max();
  auto fail = [&](const std::string& what) {
    throw InputError(spec.file, mesh.json_path, "the placed mesh spans (" + std::to_string(lo[0]) + ", " + std::to_string(lo[1]) +
                                                    ", " + std::to_string(lo[2]) + ") .. (" + std::to_string(hi[0]) + ", " +
                                                    std::to_string(hi[1]) + ", " + std::to_string(hi[2]) + "): " + what);
  };
  for (int d = 0; d < 3; ++d) {
    if (lo[d] < spec.domain_min[d] || hi[d] > spec.domain_max[d]) fail("it must lie inside the domain");
    if (!spec.tank) continue;
    if ((spec.tank->closed(d, -1) && lo[d] < spec.tank->min[d]) || (spec.tank->closed(d, 1) && hi[d] > spec.tank->max[d]))
      fail("it overlaps a closed tank wall on axis " + std::string(1, "xyz"[d]));
  }
}

}  // namespace

std::vector<Vec<3>, Eigen::aligned_allocator<Vec<3>>> mesh_particles(const CaseSpec& spec, const MeshSpec& mesh, double dx) {
  TriangleMesh source;
  try {
    source = load_obj(mesh.file);
    require_closed(source, mesh.file);
  } catch (const InputError& e) {
    throw InputError(spec.file, mesh.json_path + "/file", mesh.file + ": " + e.rule());
  }
  const TriangleMesh placed = place_mesh(std::move(source), mesh.placement);
  check_fits(spec, mesh, placed);
  return sample_inside(placed, dx);
}

}  // namespace sc
