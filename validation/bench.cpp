#include "bench.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>

#include "data_root.hpp"
#include "io/atomic_file.hpp"
#include "method/registry.hpp"
#include "observer.hpp"
#include "parallel/comm.hpp"
#include "simulator/sph_probe.hpp"
#include "probe.hpp"
#include "progress.hpp"
#include "roofline.hpp"
#include "runner.hpp"
#include "surface_bench.hpp"

namespace fs = std::filesystem;

namespace sc {

namespace {

/// Thesis Ch. 4 (Core i7 975, 3.33 GHz, OpenMP): particle counts at the start and s/step.
struct ThesisTiming {
  long sand, water;
  double seconds_per_step;
};
const std::map<std::string, ThesisTiming> thesis_timings = {
    {"thesis_duck", {11234, 23050, 3.80}},
    {"thesis_bunny_armadillos", {21456, 15525, 3.67}},
    {"thesis_bunny_winnie", {21456, 28116, 9.87}},
    {"thesis_winnie_box", {31107, 40858, 15.74}},
};
/// Zhu & Bridson 2005, §6 (a 2 GHz PowerPC G5): seconds per frame of 1/30 s for the collapsing
/// sand column of 269,322 particles on a 100³ grid, the scene `flip_zb05` reproduces.
struct PaperTiming {
  long particles;
  double seconds_per_frame;
};
const std::map<std::string, PaperTiming> paper_timings = {{"flip_zb05", {269322, 6.0}}};
constexpr double kFrameSeconds = 1.0 / 30.0;  ///< a frame of simulated time (30 frames per second)

const std::vector<std::string> default_scenes = {"thesis_duck",         "thesis_bunny_armadillos", "thesis_bunny_winnie",
                                                 "thesis_winnie_box",   "bench_water_34k",         "bench_water_104k"};

double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  const double pos = q * static_cast<double>(v.size() - 1);
  const auto k = static_cast<std::size_t>(pos);
  return k + 1 < v.size() ? v[k] + (pos - k) * (v[k + 1] - v[k]) : v[k];
}

template <int D>
json count_phases(const ParticleView<D>& view) {
  std::map<std::string, long> n;
  for (std::size_t i = 0; i < view.size(); ++i) ++n[std::string(phase_name(view.phase_of(i)))];
  return json{{"water", n["water"]}, {"sand", n["sand"]}, {"boundary", n["boundary"]}, {"total", view.size()}};
}

/// Restarts the kernel's count of this process' peak resident set (Linux: /proc/self/clear_refs),
/// so that VmHWM reads the peak from here on; false where that is not possible.
bool restart_peak_resident() {
  std::ofstream f("/proc/self/clear_refs");
  return static_cast<bool>(f << "5");
}

/// A size of /proc/self/status [bytes]: "VmHWM" (peak resident set) or "VmRSS" (resident set), 0
/// where unknown.
double status_bytes(const std::string& key) {
  std::ifstream f("/proc/self/status");
  for (std::string line; std::getline(f, line);)
    if (line.rfind(key + ":", 0) == 0) return 1024.0 * std::stod(line.substr(key.size() + 1));  // in kB
  return 0.0;
}

/// The cost of one particle, in core time: the median step's milliseconds times the cores (threads times ranks) over the
/// particles (walls included), as microseconds per particle per case step; for a method that takes
/// `own_steps` steps of its own over the `steps` case steps (DEM, MPM), also per step of its own.
void add_per_particle_times(json& entry, double median_ms, double cores, std::optional<long> own_steps, long steps) {
  const double per_step = 1e3 * median_ms * cores / entry["particles"]["total"].get<double>();
  entry["us_per_particle_step_per_core"] = per_step;
  if (!own_steps || *own_steps <= 0) return;
  const double own_per_step = static_cast<double>(*own_steps) / static_cast<double>(steps);
  entry["own_steps_per_step"] = own_per_step;
  entry["us_per_particle_own_step_per_core"] = per_step / own_per_step;
}

/// A scene decomposed over MPI ranks: the ranks, the halo's share of the step (the exchanges
/// between the ranks, stage "halo", over the mean step) and what the decomposition did.
void add_decomposition(json& entry, const std::optional<DecompositionAccount>& a) {
  if (!a) return;
  entry["ranks"] = a->ranks;
  entry["halo_share"] = entry["stage_ms_per_step"]["halo"].get<double>() / entry["ms_per_step"]["mean"].get<double>();
  entry["decomposition"] = {{"rebalances", a->rebalances},
                            {"migrated", a->migrated},
                            {"halo_particles_per_step", static_cast<double>(a->halo_particles) / static_cast<double>(a->steps)}};
}

/// The neighbour-list entries of an SPH run's last step by the phase of the list's particle.
template <int D>
ListEntries list_entries(const Method<D>& sim) {
  const SphProbe<D> probe = require_sph(sim, "the roofline");
  const ParticleSet<D>& ps = probe.particles();
  const NeighbourGrid<D>& nb = probe.neighbours();
  ListEntries e;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const auto n = static_cast<double>(nb.of(i).size());
    const Phase phase = ps.phase_of(i);
    (phase == Phase::Water ? e.water : phase == Phase::Sand ? e.sand : e.boundary) += n;
  }
  return e;
}

/// Runs `steps` steps of one scene, timing each, and returns its bench.json entry; `decompose`:
/// the scene decomposed over the MPI ranks (every rank runs it; rank 0's times are reported).
/// `entries`: set to the last step's neighbour-list entries for an SPH scene in one process.
template <int D>
json bench_scene(const CaseSpec& spec, double dx, long steps, bool decompose, std::optional<ListEntries>& entries) {
  const bool peak_known = restart_peak_resident();
  const double resident_before = status_bytes("VmRSS");  // code, libraries, what earlier scenes left
  const std::unique_ptr<Method<D>> method = make_method<D>(spec, dx, decompose);
  Method<D>& sim = *method;
  json entry{{"scene", spec.name}, {"method", spec.method}, {"spacing", dx}, {"particles", count_phases(sim.particles())}};
  sim.reset_stage_times();
  const int ranks = Comm::world().size();
  const auto cores = static_cast<double>(omp_get_max_threads()) * (decompose ? ranks : 1);
  std::vector<double> ms;
  const bool shown = !decompose || Comm::world().rank() == 0;
  Progress progress(spec.name, steps * spec.dt_max, shown ? Progress::Shown::yes : Progress::Shown::no);
  const double t_start = sim.time();
  const auto start = std::chrono::steady_clock::now();
  for (long k = 0; k < steps; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    sim.step();
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    progress.update(sim.time(), sim.steps());
  }
  progress.done(sim.time(), sim.steps());
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  json stages = json::object(), counts = json::object();
  double staged = 0.0;
  for (const StageTime& s : sim.stage_times()) {
    const double per_step = 1e3 * s.seconds / steps;
    stages[s.name] = per_step;
    staged += per_step;
    if (s.count > 0) counts[s.name] = static_cast<double>(s.count) / steps;
  }
  stages["other"] = std::max(0.0, 1e3 * total / steps - staged);
  const double simulated = sim.time() - t_start;
  entry["simulated_seconds"] = simulated;
  entry["seconds_per_frame"] = total / simulated * kFrameSeconds;  // frames of 1/30 s of simulated time
  if (!counts.empty()) entry["stage_counts_per_step"] = counts;
  entry["steps"] = steps;
  entry["ms_per_step"] = {{"median", quantile(ms, 0.5)}, {"q1", quantile(ms, 0.25)}, {"q3", quantile(ms, 0.75)},
                          {"min", quantile(ms, 0.0)},    {"max", quantile(ms, 1.0)},  {"mean", 1e3 * total / steps}};
  entry["stage_ms_per_step"] = stages;
  add_per_particle_times(entry, quantile(ms, 0.5), cores, sim.own_steps(), steps);
  if (decompose) add_decomposition(entry, require_sph(sim, "the decomposition's account").decomposition());
  entry["checksum"] = sim.checksum();
  entry["final_particles"] = count_phases(sim.particles());
  if (spec.method == "sph" && !decompose) entries = list_entries(sim);
  if (peak_known) {
    const double peak = status_bytes("VmHWM"), particles = entry["particles"]["total"].get<double>();
    entry["peak_resident_bytes"] = peak;
    entry["peak_resident_bytes_per_particle"] = peak / particles;
    entry["resident_before_bytes"] = resident_before;
    entry["scene_peak_bytes_per_particle"] = (peak - resident_before) / particles;
  }
  return entry;
}

json bench_any(const CaseSpec& spec, double dx, long steps, bool decompose, std::optional<ListEntries>& entries) {
  check_method(spec);
  if (decompose) check_decomposable(spec);
  return spec.dimension == 2 ? bench_scene<2>(spec, dx, steps, decompose, entries)
                             : bench_scene<3>(spec, dx, steps, decompose, entries);
}

/// What adaptivity buys: the same scene without its "adaptive" section, timed over the same
/// steps, as entry["uniform"], and the ratios of mean ms/step and of moving particles at the end.
void add_uniform_comparison(const CaseSpec& spec, double dx, long steps, json& entry) {
  CaseSpec uniform = spec;
  uniform.adaptive.reset();
  uniform.name = spec.name + " (uniform)";
  std::optional<ListEntries> unused;
  const json u = bench_any(uniform, dx, steps, false, unused);
  entry["uniform"] = u;
  entry["adaptive_speedup"] = u["ms_per_step"]["mean"].get<double>() / entry["ms_per_step"]["mean"].get<double>();
  const auto moving = [](const json& e) {
    return static_cast<double>(e["final_particles"]["water"].get<long>() + e["final_particles"]["sand"].get<long>());
  };
  entry["particle_ratio_final"] = moving(u) / moving(entry);
}

void add_thesis_comparison(json& entry) {
  const auto it = thesis_timings.find(entry.at("scene").get<std::string>());
  if (it == thesis_timings.end()) return;
  const ThesisTiming& t = it->second;
  const double median = entry["ms_per_step"]["median"];
  entry["thesis"] = {{"sand", t.sand}, {"water", t.water}, {"seconds_per_step", t.seconds_per_step}};
  entry["speedup_vs_thesis"] = 1e3 * t.seconds_per_step / median;
}

void add_paper_comparison(json& entry) {
  const auto it = paper_timings.find(entry.at("scene").get<std::string>());
  if (it == paper_timings.end()) return;
  entry["paper"] = {{"particles", it->second.particles}, {"seconds_per_frame", it->second.seconds_per_frame}};
  entry["speedup_vs_paper"] = it->second.seconds_per_frame / entry.at("seconds_per_frame").get<double>();
}

void print_table(const json& entries) {
  std::printf("%-24s %8s %8s %8s %4s %10s %9s %9s  %s\n", "scene", "water", "sand", "boundary", "thr", "ms/step", "q1-q3",
              "speedup", "stages (ms/step)");
  for (const json& e : entries) {
    if (e.contains("error")) continue;
    const json& p = e["particles"];
    const json& t = e["ms_per_step"];
    std::string stages;
    for (const auto& [name, v] : e["stage_ms_per_step"].items())
      if (v.get<double>() >= 0.05) stages += name + " " + format_number(std::round(10.0 * v.get<double>()) / 10.0) + "  ";
    char spread[32];
    std::snprintf(spread, sizeof spread, "%.1f-%.1f", t["q1"].get<double>(), t["q3"].get<double>());
    const std::string speedup = e.contains("speedup_vs_thesis") ? format_number(std::round(e["speedup_vs_thesis"].get<double>())) + "x" : "-";
    std::printf("%-24s %8ld %8ld %8ld %4d %10.1f %9s %9s  %s\n", e["scene"].get<std::string>().c_str(), p["water"].get<long>(),
                p["sand"].get<long>(), p["boundary"].get<long>(), e["threads"].get<int>(), t["median"].get<double>(), spread,
                speedup.c_str(), stages.c_str());
    if (e.contains("speedup_vs_paper")) {
      std::string counted;
      for (const auto& [name, v] : e["stage_counts_per_step"].items())
        counted += "  " + name + " " + format_number(std::round(10.0 * v.get<double>()) / 10.0) + " iterations/step";
      std::printf("%-24s %.3f s per frame of 1/30 s (%ld steps over %.4f s), paper %.1f s: %.1fx faster%s\n", "",
                  e["seconds_per_frame"].get<double>(), e["steps"].get<long>(), e["simulated_seconds"].get<double>(),
                  e["paper"]["seconds_per_frame"].get<double>(), e["speedup_vs_paper"].get<double>(), counted.c_str());
    }
    if (e.contains("peak_resident_bytes"))
      std::printf("%-24s peak resident set %.0f MB: %.0f bytes per particle, %.0f above the %.0f MB held before the scene\n", "",
                  e["peak_resident_bytes"].get<double>() / 1e6, e["peak_resident_bytes_per_particle"].get<double>(),
                  e["scene_peak_bytes_per_particle"].get<double>(), e["resident_before_bytes"].get<double>() / 1e6);
    if (e.contains("us_per_particle_own_step_per_core"))
      std::printf("%-24s %.3f us per particle per step per core; %.1f steps of its own per step: %.3f us per particle per own step per core\n", "",
                  e["us_per_particle_step_per_core"].get<double>(), e["own_steps_per_step"].get<double>(),
                  e["us_per_particle_own_step_per_core"].get<double>());
    else
      std::printf("%-24s %.3f us per particle per step per core\n", "", e["us_per_particle_step_per_core"].get<double>());
    if (e.contains("roofline")) {
      std::string line;
      for (const auto& [name, st] : e["roofline"]["stages"].items()) {
        if (!st.contains("fraction_of_limit")) continue;
        char part[160];
        std::snprintf(part, sizeof part, "  %s %.2f Gpairs/s, %.0f B/particle, %.0f%% of the %s limit;", name.c_str(),
                      st["pair_evaluations_per_s"].get<double>() / 1e9, st["bytes_per_particle"].get<double>(),
                      100.0 * st["fraction_of_limit"].get<double>(), st["bound"].get<std::string>().c_str());
        line += part;
      }
      std::printf("%-24s roofline:%s\n", "", line.c_str());
    }
    if (e.contains("adaptive_speedup"))
      std::printf("%-24s uniform %.1f ms/step (mean) vs adaptive %.1f: %.2fx faster; %.2fx fewer moving particles at the end\n", "",
                  e["uniform"]["ms_per_step"]["mean"].get<double>(), t["mean"].get<double>(), e["adaptive_speedup"].get<double>(),
                  e["particle_ratio_final"].get<double>());
  }
}

}  // namespace

int bench(const BenchOptions& opt) {
  if (opt.probe) {
    const std::vector<ProbeRow> rows = run_probe(opt.threads);
    fs::create_directories(opt.out_dir);
    write_file_atomic(opt.out_dir + "/probe.json", probe_document(rows).dump(2) + "\n");
    std::cout << probe_table(rows);
    return kSuccess;
  }
  if (opt.threads > 0) omp_set_num_threads(opt.threads);
  const bool decompose = Comm::world().size() > 1, writer = Comm::world().rank() == 0;
  if (opt.surface) {
    const json document = run_surface_bench();
    fs::create_directories(opt.out_dir);
    write_file_atomic(opt.out_dir + "/surface.json", document.dump(2) + "\n");
    std::cout << surface_bench_table(document);
    return kSuccess;
  }
  const std::string cases_dir = opt.cases_dir.empty() ? data_path("cases") : opt.cases_dir;
  const std::vector<std::string>& scenes = opt.scenes.empty() ? default_scenes : opt.scenes;
  // The roofline's limits: a --limits file is read before any scene runs or anything is written
  // (bad input: exit 2); without one they are measured once, at the first SPH scene.
  std::optional<ProbeRow> limits;
  if (!opt.limits.empty()) limits = bench_limits(opt.limits, omp_get_max_threads());
  if (writer) fs::create_directories(opt.out_dir);
  json entries = json::array();
  int exit_code = kSuccess;
  for (const std::string& name : scenes) {
    const std::string file = cases_dir + "/" + name + "/case.json";
    if (!fs::exists(file)) throw InputError(file, "", "no scene named '" + name + "' (see " + cases_dir + ")");
    const CaseSpec spec = opt.method.empty() ? load_case(file) : with_method(load_case(file), opt.method);
    const double dx = spec.tiers.at("full").spacings.back();
    check_particle_count(spec, dx, opt.max_particles, "/tiers/full/spacings");
    const long steps = opt.steps > 0 ? opt.steps : (name.rfind("bench_water", 0) == 0 ? 200 : 100);
    try {
      std::optional<ListEntries> list;
      json entry = bench_any(spec, dx, steps, decompose, list);
      entry["threads"] = omp_get_max_threads();
      if (list) {
        if (!limits) limits = bench_limits(opt.limits, omp_get_max_threads());
        entry["roofline"] = roofline(spec.dimension, *list, entry["particles"]["total"].get<double>(),
                                     entry["stage_ms_per_step"], spec.water.gradient_correction, *limits,
                                     opt.limits.empty() ? "measured" : opt.limits);
      }
      add_thesis_comparison(entry);
      add_paper_comparison(entry);
      if (spec.adaptive) add_uniform_comparison(spec, dx, steps, entry);
      entries.push_back(entry);
    } catch (const BlowUpError& e) {
      if (writer) std::cerr << "error: " << name << ": " << e.what() << "\n";
      entries.push_back({{"scene", name}, {"error", e.what()}});
      exit_code = kBlowUp;
    }
    if (writer)
      write_file_atomic(opt.out_dir + "/bench.json",
                        json{{"compiler", SANDCASTLE_COMPILER}, {"scenes", entries}}.dump(2) + "\n");
  }
  if (writer) print_table(entries);
  return exit_code;
}

}  // namespace sc
