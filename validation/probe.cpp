#include "probe.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <sstream>

namespace sc {

namespace {

constexpr std::size_t kTriadElements = std::size_t{1} << 24;  // 128 MiB per array, 384 MiB in all
constexpr int kPasses = 5;
constexpr int kChainsPerThread = 16;                           // beyond the FP pipelines' latency x width
constexpr long kChainIterations = 20'000'000;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double triad_bandwidth(int threads) {
  omp_set_num_threads(threads);
  std::vector<double> a(kTriadElements), b(kTriadElements, 1.0), c(kTriadElements, 2.0);
  triad(a, b, c, 0.5);  // first touch by the threads that use the pages
  double best = 0.0;
  for (int pass = 0; pass < kPasses; ++pass) {
    const auto t0 = std::chrono::steady_clock::now();
    triad(a, b, c, 0.5);
    best = std::max(best, 24.0 * static_cast<double>(kTriadElements) / seconds_since(t0));
  }
  return best;
}

double chain_flops(int threads) {
  omp_set_num_threads(threads);
  double best = 0.0;
  for (int pass = 0; pass < kPasses; ++pass) {
    const auto t0 = std::chrono::steady_clock::now();
    const double sum = multiply_add_chains(kChainIterations, kChainsPerThread * threads, 1.0, 0.999999, 1e-6);
    const double t = seconds_since(t0);
    if (sum > 0.0) best = std::max(best, 2.0 * kChainIterations * kChainsPerThread * threads / t);
  }
  return best;
}

}  // namespace

void triad(std::vector<double>& a, const std::vector<double>& b, const std::vector<double>& c, double s) {
  const long n = static_cast<long>(a.size());
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) a[i] = b[i] + s * c[i];
}

double multiply_add_chains(long iterations, int chains, double x0, double m, double c) {
  constexpr int width = 8;  // chains advanced together by one thread
  const int groups = (chains + width - 1) / width;
  std::vector<double> total(static_cast<std::size_t>(groups), 0.0);
#pragma omp parallel for schedule(static)
  for (int g = 0; g < groups; ++g) {
    double x[width];
    for (double& v : x) v = x0;
    for (long k = 0; k < iterations; ++k)
      for (double& v : x) v = v * m + c;
    const int live = std::min(width, chains - g * width);
    for (int j = 0; j < live; ++j) total[static_cast<std::size_t>(g)] += x[j];
  }
  double sum = 0.0;
  for (const double t : total) sum += t;  // fixed order
  return sum;
}

ProbeRow probe_row(int threads) { return {threads, triad_bandwidth(threads), chain_flops(threads)}; }

std::vector<ProbeRow> run_probe(int max_threads) {
  const int top = max_threads > 0 ? max_threads : omp_get_max_threads();
  std::vector<ProbeRow> rows;
  for (int t = 1; t <= top; ++t) rows.push_back(probe_row(t));
  omp_set_num_threads(top);
  return rows;
}

json probe_document(const std::vector<ProbeRow>& rows) {
  json list = json::array();
  for (const ProbeRow& r : rows)
    list.push_back({{"threads", r.threads}, {"bandwidth_bytes_per_s", r.bandwidth}, {"flops_per_s", r.flops}});
  return {{"kernels",
           {{"bandwidth", "STREAM triad a = b + s c, 24 bytes per element, 3 arrays of 128 MiB, best of 5"},
            {"flops", "independent chains x = x m + c, 2 flops each, no FMA, best of 5"}}},
          {"rows", list}};
}

std::string probe_table(const std::vector<ProbeRow>& rows) {
  std::ostringstream o;
  o << "threads  bandwidth [GB/s]  double flops [Gflop/s]\n";
  for (const ProbeRow& r : rows) {
    char line[96];
    std::snprintf(line, sizeof line, "%7d  %16.2f  %22.2f\n", r.threads, r.bandwidth / 1e9, r.flops / 1e9);
    o << line;
  }
  return o.str();
}

}  // namespace sc
