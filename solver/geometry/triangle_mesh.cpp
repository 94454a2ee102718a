#include "geometry/triangle_mesh.hpp"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "core/errors.hpp"

namespace sc {

Vec<3> TriangleMesh::bbox_min() const {
  Vec<3> lo = Vec<3>::Constant(INFINITY);
  for (const Vec<3>& v : vertices) lo = lo.cwiseMin(v);
  return lo;
}

Vec<3> TriangleMesh::bbox_max() const {
  Vec<3> hi = Vec<3>::Constant(-INFINITY);
  for (const Vec<3>& v : vertices) hi = hi.cwiseMax(v);
  return hi;
}

double TriangleMesh::signed_volume() const {
  double six_v = 0.0;
  for (const auto& t : triangles) six_v += vertices[t[0]].dot(vertices[t[1]].cross(vertices[t[2]]));
  return six_v / 6.0;
}

namespace {

/// tinyobjloader reads an unparsable coordinate ("nan", "1.#IND") as 0 without an error, which would
/// silently move a vertex; every `v` line is therefore checked for three finite numbers first.
void check_vertex_lines(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  for (long number = 1; std::getline(in, line); ++number) {
    if (line.rfind("v ", 0) != 0 && line.rfind("v\t", 0) != 0) continue;
    std::istringstream fields(line.substr(2));
    std::string token;
    for (int c = 0; c < 3; ++c) {
      char* end = nullptr;
      const double value = (fields >> token) ? std::strtod(token.c_str(), &end) : NAN;
      if (!std::isfinite(value) || *end != '\0')
        throw InputError(path, "", "line " + std::to_string(number) + ": a vertex needs three finite coordinates");
    }
  }
}

}  // namespace

TriangleMesh load_obj(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw InputError(path, "", "mesh file not found");
  check_vertex_lines(path);
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path, config)) throw InputError(path, "", "cannot read the OBJ mesh: " + reader.Error());
  const auto& coords = reader.GetAttrib().vertices;
  TriangleMesh mesh;
  for (std::size_t k = 0; k + 2 < coords.size(); k += 3) {
    mesh.vertices.emplace_back(coords[k], coords[k + 1], coords[k + 2]);
  }
  for (const auto& shape : reader.GetShapes()) {
    const auto& idx = shape.mesh.indices;
    for (std::size_t k = 0; k + 2 < idx.size(); k += 3) {
      std::array<std::uint32_t, 3> t{};
      for (int c = 0; c < 3; ++c) {
        const int vi = idx[k + c].vertex_index;
        if (vi < 0 || static_cast<std::size_t>(vi) >= mesh.vertices.size())
          throw InputError(path, "", "a face refers to a vertex that does not exist");
        t[c] = static_cast<std::uint32_t>(vi);
      }
      mesh.triangles.push_back(t);
    }
  }
  if (mesh.triangles.empty()) throw InputError(path, "", "the mesh holds no triangle");
  return mesh;
}

EdgeReport edge_report(const TriangleMesh& mesh) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
  for (const auto& t : mesh.triangles)
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t a = t[c], b = t[(c + 1) % 3];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  EdgeReport r;
  r.edges = uses.size();
  for (const auto& [edge, count] : uses) {
    if (count == 1) ++r.boundary;
    if (count > 2) ++r.non_manifold;
  }
  return r;
}

void require_closed(const TriangleMesh& mesh, const std::string& path) {
  const EdgeReport r = edge_report(mesh);
  if (r.boundary > 0 || r.non_manifold > 0)
    throw InputError(path, "", "the mesh is not closed (" + std::to_string(r.boundary) + " edges border a hole, " +
                                   std::to_string(r.non_manifold) +
                                   " are shared by more than two triangles): its inside is not defined; close it first");
}

TriangleMesh place_mesh(TriangleMesh mesh, const MeshPlacement& p) {
  if (p.up_axis == "y")
    for (Vec<3>& v : mesh.vertices) v = Vec<3>(v.x(), -v.z(), v.y());  // rotation by +90° about x
  double scale = p.scale;
  if (p.size > 0.0) scale = p.size / (mesh.bbox_max() - mesh.bbox_min()).maxCoeff();
  for (Vec<3>& v : mesh.vertices) v *= scale;
  Vec<3> shift = Vec<3>::Zero();
  if (p.min_corner.size() == 3) shift = Vec<3>(p.min_corner[0], p.min_corner[1], p.min_corner[2]) - mesh.bbox_min();
  else if (p.translation.size() == 3) shift = Vec<3>(p.translation[0], p.translation[1], p.translation[2]);
  for (Vec<3>& v : mesh.vertices) v += shift;
  return mesh;
}

}  // namespace sc
