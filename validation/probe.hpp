// `sandcastle bench --probe`: what this machine can do, the limits a stage's speed is read against
// (docs/performance.md). Two kernels, each at 1 .. N OpenMP threads:
// - memory bandwidth: the STREAM triad a_i = b_i + s c_i over three arrays far larger than any cache,
//   counted as 24 bytes per element (two reads and a write; write-allocate traffic not counted, as
//   STREAM counts it), best of several passes;
// - double-precision throughput: independent chains x ← x·m + c per thread (two flops each; no
//   fused multiply-add, the build's -ffp-contract=off), enough chains to fill the pipelines, best
//   of several passes.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "io/json_reader.hpp"

namespace sc {

/// a[i] = b[i] + s c[i] for every i, the threads sharing the range in static blocks.
void triad(std::vector<double>& a, const std::vector<double>& b, const std::vector<double>& c, double s);

/// `chains` independent x ← x·m + c from x = x0, `iterations` times each, in parallel; returns the
/// sum of the chains' final values (so no chain's work can be dropped).
double multiply_add_chains(long iterations, int chains, double x0, double m, double c);

struct ProbeRow {
  int threads = 0;
  double bandwidth = 0.0;  ///< [bytes/s] triad
  double flops = 0.0;      ///< [flop/s] multiply-add chains
};

/// The probe at `threads` threads (OpenMP's thread count is left at `threads`).
ProbeRow probe_row(int threads);

/// The probe at 1 .. max_threads threads (0: OpenMP's default maximum).
std::vector<ProbeRow> run_probe(int max_threads);

/// probe.json's document and the table printed for it.
json probe_document(const std::vector<ProbeRow>& rows);
std::string probe_table(const std::vector<ProbeRow>& rows);

}  // namespace sc
