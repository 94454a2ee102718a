// `sandcastle bench --surface`: the time of one surface reconstruction (solver/surface/, Zhu &
// Bridson 2005), the stage `run --surface` adds to every frame. Two samplings of one cubic lattice
// block of 41³ = 68,921 particles (about the particle count of the thesis' largest scene):
// - "quarter_spacing": voxels of a quarter of the spacing, the default of `run --surface`;
// - "grid_250": voxels sized so that the sampled box spans 250 voxels a side, the grid on which Zhu
//   & Bridson report 40-50 s per frame (their §6).
// Each is timed as the median of a few repeats; docs/performance.md.
#pragma once
#include <string>

#include "io/json_reader.hpp"

namespace sc {

/// Times both samplings at the current OpenMP thread count: their document for surface.json.
json run_surface_bench();

/// The table printed for it.
std::string surface_bench_table(const json& document);

}  // namespace sc
