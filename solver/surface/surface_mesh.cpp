#include "surface/surface_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <openvdb/openvdb.h>
#include <openvdb/tools/Filter.h>
#include <openvdb/tools/VolumeToMesh.h>

#include "neighbours/cell_grid.hpp"
#include "surface/implicit_surface.hpp"

namespace sc::surface {

namespace {

using Leaf = openvdb::DoubleTree::LeafNodeType;
using Origin = std::array<int, 3>;

/// The origins of the 8³-voxel leaves holding a voxel within `reach` of some particle (voxel index
/// i at i·h), sorted.
std::vector<Origin> leaf_origins(std::span<const Vec<3>> x, double h, double reach) {
  std::vector<Origin> out;
  for (const auto& p : x) {
    Origin lo{}, hi{};
    for (int d = 0; d < 3; ++d) {
      lo[d] = static_cast<int>(std::ceil((p[d] - reach) / h)) & ~(Leaf::DIM - 1);
      hi[d] = static_cast<int>(std::floor((p[d] + reach) / h)) & ~(Leaf::DIM - 1);
    }
    for (int i = lo[0]; i <= hi[0]; i += Leaf::DIM)
      for (int j = lo[1]; j <= hi[1]; j += Leaf::DIM)
        for (int k = lo[2]; k <= hi[2]; k += Leaf::DIM) out.push_back({i, j, k});
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

/// φ of the particles at every voxel of the leaf at `origin`; a voxel with no particle within
/// reach keeps the background (outside) and stays inactive. Gathered per leaf: the particles near
/// the leaf once (the cells within reach of its box, in the grid's fixed order), then each of them
/// added to the averages of the leaf's voxels within its reach, so a voxel's sums run over the
/// particles in that order whatever the thread.
std::unique_ptr<Leaf> sample_leaf(const Origin& origin, const CellGrid<3>& cells, std::span<const Vec<3>> x, double h,
                                  double radius, double reach) {
  constexpr int n = static_cast<int>(Leaf::DIM);
  auto leaf = std::make_unique<Leaf>(openvdb::Coord(origin[0], origin[1], origin[2]), reach, false);
  const double half = 0.5 * (n - 1) * h;  // from the leaf's centre to its outer voxels, per axis
  const Vec<3> centre(origin[0] * h + half, origin[1] * h + half, origin[2] * h + half);
  const int rings = static_cast<int>(std::ceil((std::sqrt(3.0) * half + reach) / (0.5 * reach)));
  std::vector<SurfaceAverage<3>> averages;
  averages.reserve(Leaf::SIZE);
  for (openvdb::Index v = 0; v < Leaf::SIZE; ++v) {
    const openvdb::Coord ijk = leaf->offsetToGlobalCoord(v);
    averages.emplace_back(Vec<3>(ijk.x() * h, ijk.y() * h, ijk.z() * h), reach);
  }
  // The leaf's voxels along an axis whose distance to x_d is below reach: [first, last].
  const auto span = [&](int d, double xd, double r) {
    const int first = std::max(0, static_cast<int>(std::ceil((xd - r) / h)) - origin[d]);
    const int last = std::min(n - 1, static_cast<int>(std::floor((xd + r) / h)) - origin[d]);
    return std::pair{first, last};
  };
  cells.for_each_near(centre, [&](std::uint32_t j) {
    const Vec<3>& p = x[j];
    const auto [i0, i1] = span(0, p[0], reach);
    for (int i = i0; i <= i1; ++i) {
      const double dx = (origin[0] + i) * h - p[0], ry = std::sqrt(std::max(0.0, reach * reach - dx * dx));
      const auto [j0, j1] = span(1, p[1], ry);
      for (int k = j0; k <= j1; ++k) {
        const double dy = (origin[1] + k) * h - p[1], rz = std::sqrt(std::max(0.0, ry * ry - dy * dy));
        const auto [l0, l1] = span(2, p[2], rz);
        for (int l = l0; l <= l1; ++l) averages[static_cast<std::size_t>((i * n + k) * n + l)].add(p, radius);
      }
    }
  }, rings);
  for (openvdb::Index v = 0; v < Leaf::SIZE; ++v)
    if (!averages[v].empty()) leaf->setValueOn(v, averages[v].phi());
  return leaf;
}

/// The sampled φ on a sparse grid of voxel h, background `reach` (outside).
openvdb::DoubleGrid::Ptr sample(std::span<const Vec<3>> x, double h, double radius, double reach) {
  CellGrid<3> cells;  // cells of R/2, the 5³ around a voxel: fewer candidates than 3³ of R
  cells.build(x, 0.5 * reach);
  const std::vector<Origin> origins = leaf_origins(x, h, reach);
  std::vector<std::unique_ptr<Leaf>> leaves(origins.size());
  const long n = static_cast<long>(origins.size());
#pragma omp parallel for schedule(dynamic, 8)
  for (long l = 0; l < n; ++l) leaves[l] = sample_leaf(origins[l], cells, x, h, radius, reach);
  auto grid = openvdb::DoubleGrid::create(reach);
  grid->setTransform(openvdb::math::Transform::createLinearTransform(h));
  for (auto& leaf : leaves) grid->tree().addLeaf(leaf.release());
  return grid;
}

}  // namespace

SurfaceMesh reconstruct_surface(std::span<const Vec<3>> x, const SurfaceOptions& options) {
  if (!(options.spacing > 0.0) || !(options.voxel_fraction > 0.0) || options.smoothing_passes < 0)
    throw std::invalid_argument("reconstruct_surface: spacing and voxel_fraction must be positive");
  static std::once_flag initialised;
  std::call_once(initialised, [] { openvdb::initialize(); });
  SurfaceMesh mesh;
  if (x.empty()) return mesh;
  const double h = options.voxel_fraction * options.spacing;
  const openvdb::DoubleGrid::Ptr grid = sample(x, h, options.radius(), options.reach());
  if (options.smoothing_passes > 0) openvdb::tools::Filter<openvdb::DoubleGrid>(*grid).mean(1, options.smoothing_passes);
  std::vector<openvdb::Vec3s> points;
  std::vector<openvdb::Vec4I> quads;
  openvdb::tools::volumeToMesh(*grid, points, quads, 0.0);
  mesh.points.reserve(points.size());
  for (const auto& p : points) mesh.points.emplace_back(p.x(), p.y(), p.z());
  mesh.triangles.reserve(2 * quads.size());
  for (const auto& q : quads) {  // OpenVDB winds the quads counter-clockwise seen from outside
    mesh.triangles.push_back({q[0], q[1], q[2]});
    mesh.triangles.push_back({q[0], q[2], q[3]});
  }
  return mesh;
}

void attach_saturation(SurfaceMesh& mesh, std::span<const Vec<3>> x, std::span<const double> saturation,
                       const SurfaceOptions& options) {
  if (x.size() != saturation.size()) throw std::invalid_argument("attach_saturation: one saturation per particle");
  mesh.saturation.assign(mesh.points.size(), 0.0);
  if (x.empty()) return;
  CellGrid<3> cells;
  const double reach = options.reach();
  cells.build(x, 0.5 * reach);
  const long n = static_cast<long>(mesh.points.size());
#pragma omp parallel for schedule(static)
  for (long v = 0; v < n; ++v) {
    const Vec<3>& at = mesh.points[v];
    double w_sum = 0.0, s_sum = 0.0, nearest = INFINITY;
    std::size_t closest = 0;
    cells.for_each_near(at, [&](std::uint32_t j) {
      const double d2 = (x[j] - at).squaredNorm();
      if (d2 < nearest) {
        nearest = d2;
        closest = j;
      }
      const double w = surface_kernel(d2 / (reach * reach));
      w_sum += w;
      s_sum += w * saturation[j];
    }, 2);
    mesh.saturation[v] = w_sum > 0.0 ? s_sum / w_sum : saturation[closest];
  }
}

double enclosed_volume(const SurfaceMesh& mesh) {
  double v = 0.0;
  for (const auto& t : mesh.triangles)
    v += mesh.points[t[0]].dot(mesh.points[t[1]].cross(mesh.points[t[2]]));
  return v / 6.0;
}

bool is_closed_and_oriented(const SurfaceMesh& mesh) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;  // edge a -> b: how many triangles run along it
  for (const auto& t : mesh.triangles) {
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) return false;
    for (int e = 0; e < 3; ++e) ++directed[{t[e], t[(e + 1) % 3]}];
  }
  for (const auto& [edge, count] : directed) {
    const auto back = directed.find({edge.second, edge.first});
    if (count != 1 || back == directed.end() || back->second != 1) return false;
  }
  return !mesh.triangles.empty();
}

std::string vtp_document(const SurfaceMesh& mesh) {
  std::ostringstream o;
  o.precision(9);  // OpenVDB's points are single precision
  o << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
    << "<PolyData>\n<Piece NumberOfPoints=\"" << mesh.points.size() << "\" NumberOfPolys=\"" << mesh.triangles.size()
    << "\">\n<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (const auto& p : mesh.points) o << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
  o << "</DataArray>\n</Points>\n<Polys>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (const auto& t : mesh.triangles) o << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
  o << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  for (std::size_t k = 1; k <= mesh.triangles.size(); ++k)
    o << 3 * k << (k % 16 == 0 || k == mesh.triangles.size() ? '\n' : ' ');
  o << "</DataArray>\n</Polys>\n";
  if (!mesh.saturation.empty()) {
    o << "<PointData Scalars=\"saturation\">\n<DataArray type=\"Float64\" Name=\"saturation\" format=\"ascii\">\n";
    for (const double s : mesh.saturation) o << s << '\n';
    o << "</DataArray>\n</PointData>\n";
  }
  o << "</Piece>\n</PolyData>\n</VTKFile>\n";
  return o.str();
}

}  // namespace sc::surface
