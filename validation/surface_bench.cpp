#include "surface_bench.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include "surface/surface_mesh.hpp"

namespace sc {

namespace {

constexpr int kLatticeSide = 41;     // particles along each edge of the block: 41³ = 68,921
constexpr double kSpacing = 0.01;    // [m]
constexpr int kRepeats = 3;          // timed reconstructions per sampling (the median is reported)
constexpr double kGridSide = 250.0;  // voxels along the sampled box's edge for "grid_250"

std::vector<Vec<3>> lattice_block() {
  std::vector<Vec<3>> x;
  x.reserve(static_cast<std::size_t>(kLatticeSide) * kLatticeSide * kLatticeSide);
  for (int i = 0; i < kLatticeSide; ++i)
    for (int j = 0; j < kLatticeSide; ++j)
      for (int k = 0; k < kLatticeSide; ++k) x.emplace_back(i * kSpacing, j * kSpacing, k * kSpacing);
  return x;
}

/// One sampling: the median wall time of kRepeats reconstructions, and the mesh's size.
json time_reconstruction(const std::string& name, const std::vector<Vec<3>>& x, double voxel_fraction) {
  const surface::SurfaceOptions options{.spacing = kSpacing, .voxel_fraction = voxel_fraction};
  std::vector<double> seconds;
  surface::SurfaceMesh mesh;
  for (int r = 0; r < kRepeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    mesh = surface::reconstruct_surface(x, options);
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(seconds.begin(), seconds.end());
  const double box = (kLatticeSide - 1) * kSpacing + 2.0 * options.reach();  // the particles' box grown by R
  return {{"sampling", name}, {"particles", x.size()}, {"voxel", voxel_fraction * kSpacing},
          {"voxel_over_spacing", voxel_fraction}, {"grid_side_voxels", box / (voxel_fraction * kSpacing)},
          {"seconds", seconds[kRepeats / 2]}, {"seconds_min", seconds.front()}, {"seconds_max", seconds.back()},
          {"repeats", kRepeats}, {"points", mesh.points.size()}, {"triangles", mesh.triangles.size()}};
}

}  // namespace

json run_surface_bench() {
  const std::vector<Vec<3>> x = lattice_block();
  const double box_over_spacing = (kLatticeSide - 1) + 2.0 * surface::reach_factor;
  json rows = json::array();
  rows.push_back(time_reconstruction("quarter_spacing", x, 0.25));
  rows.push_back(time_reconstruction("grid_250", x, box_over_spacing / kGridSide));
  return {{"threads", omp_get_max_threads()},
          {"paper", {{"grid_side_voxels", kGridSide}, {"seconds_per_frame", {40.0, 50.0}},
                     {"source", "Zhu & Bridson 2005, section 6"}}},
          {"samplings", rows}};
}

std::string surface_bench_table(const json& document) {
  std::string out = "sampling            particles  voxel/s  grid side  threads   seconds (min-max)      points  triangles\n";
  for (const json& r : document.at("samplings")) {
    char line[200];
    std::snprintf(line, sizeof line, "%-18s %10ld %8.3f %10.0f %8d %9.3f (%.3f-%.3f) %10ld %10ld\n",
                  r.at("sampling").get<std::string>().c_str(), r.at("particles").get<long>(),
                  r.at("voxel_over_spacing").get<double>(), r.at("grid_side_voxels").get<double>(),
                  document.at("threads").get<int>(), r.at("seconds").get<double>(), r.at("seconds_min").get<double>(),
                  r.at("seconds_max").get<double>(), r.at("points").get<long>(), r.at("triangles").get<long>());
    out += line;
  }
  return out + "Zhu & Bridson 2005: 40-50 s per frame on a 250^3 grid\n";
}

}  // namespace sc
