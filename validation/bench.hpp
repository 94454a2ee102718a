// `sandcastle bench`: times scenes step by step and compares them with the thesis' timings.
#pragma once
#include <string>
#include <vector>

#include "scene/scene_builder.hpp"

namespace sc {

struct BenchOptions {
  std::vector<std::string> scenes;  ///< case names; empty = the four thesis scenes and the two water benchmarks
  long steps = 0;                   ///< 0 = the scene's default (200 for the water benchmarks, 100 otherwise)
  int threads = 0;                  ///< OpenMP threads; 0 = OpenMP's default (OMP_NUM_THREADS)
  std::string out_dir;
  std::string cases_dir;            ///< default: the repository's cases/
  std::string method;               ///< run every scene by this method (one it supports); empty = the scene's own
  double max_particles = kDefaultMaxParticles;      ///< estimated particles above which a scene is refused (--max-particles)
  bool probe = false;  ///< instead of scenes, measure the machine's limits at 1 .. threads threads (validation/probe.hpp)
  bool surface = false;  ///< instead of scenes, time the surface reconstruction (validation/surface_bench.hpp)
  std::string limits;    ///< probe.json whose row at the run's thread count the roofline reads; empty = measure it
};

/// Runs every scene at the finest spacing of its full tier and writes out_dir/bench.json: particle
/// counts, threads, ms/step (median, quartiles, min, max over the steps), the per-stage times
/// (StageTimers) and counts (FLIP's CG iterations), seconds per frame of 1/30 s of simulated time,
/// and the speed-up against the thesis' s/step (its four scenes) or the paper's s/frame
/// (`flip_zb05`, Zhu & Bridson 2005), and for SPH scenes in one process the roofline of its pair
/// stages against the probe's limits (validation/roofline.hpp). Prints a table. Returns the exit code. With `probe`: writes
/// out_dir/probe.json (memory bandwidth and double-precision throughput per thread count) instead;
/// with `surface`: out_dir/surface.json (the reconstruction of a 68,921-particle block) instead.
int bench(const BenchOptions& options);

}  // namespace sc
