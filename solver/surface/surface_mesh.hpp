// Surface meshes of particle sets: the zero level set of the Zhu & Bridson implicit function
// (surface/implicit_surface.hpp), sampled on a sparse voxel grid finer than the particles and
// meshed by OpenVDB's volume-to-mesh (Debian libopenvdb-dev). 3-D only.
#pragma once
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/types.hpp"
#include "surface/implicit_surface.hpp"

namespace sc::surface {

struct SurfaceOptions {
  double spacing = 0.0;          ///< the particles' mean spacing s [m]
  double voxel_fraction = 0.25;  ///< voxel edge over s
  int smoothing_passes = 1;      ///< 3³ mean-filter passes over the sampled φ (Zhu & Bridson: one)

  double radius() const { return lattice_radius_factor * spacing; }  ///< every particle's radius r [m]
  double reach() const { return reach_factor * spacing; }            ///< the neighbourhood R [m]
};

/// A closed triangle mesh, triangles counter-clockwise seen from outside (normals point out).
struct SurfaceMesh {
  std::vector<Vec<3>> points;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<double> saturation;  ///< per point, when the particles carry one (wet sand shown darker); else empty
};

/// The surface of the particles at `x` [Zhu-Bridson 2005: Surface Reconstruction]: φ of
/// SurfaceAverage (radius and neighbourhood of `options`) at the voxels within R of a particle, gathered per voxel in a fixed order, then
/// `smoothing_passes` mean-filter passes ("additional grid smoothing reduces bump artifacts") and
/// the zero level set meshed (quads split into triangles). The same particles give the same mesh
/// with any number of threads.
SurfaceMesh reconstruct_surface(std::span<const Vec<3>> x, const SurfaceOptions& options);

/// Sets mesh.saturation: per point the mean of the particles' `saturation` within R of it, weighted by
/// the kernel of SurfaceAverage (k = (1 − |x − x_i|²/R²)³), gathered in a fixed order; the nearest
/// particle's where none is within R (a vertex lies within R of the particles that made it).
void attach_saturation(SurfaceMesh& mesh, std::span<const Vec<3>> x, std::span<const double> saturation,
                       const SurfaceOptions& options);

/// The volume a closed mesh encloses, Σ_t x_0·(x_1 × x_2)/6 over its triangles (positive when its
/// normals point out) [m³].
double enclosed_volume(const SurfaceMesh& mesh);

/// Whether every edge of the mesh is shared by exactly two triangles that run along it in opposite
/// directions (closed, manifold along edges, consistently oriented) and no triangle repeats a vertex.
bool is_closed_and_oriented(const SurfaceMesh& mesh);

/// The VTP document (VTK polygonal data, ASCII, ParaView) of a mesh: its points and triangles, and
/// the point array "saturation" when the mesh has one.
std::string vtp_document(const SurfaceMesh& mesh);

}  // namespace sc::surface
