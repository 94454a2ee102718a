// The case file (cases/<name>/case.json): scene, parameters, validation and tiers.
// The format is documented in cases/README.md; every field is checked on load. Each physics folder
// owns its section's parameters, reader and derived values (water/water_section, sand/sand_params,
// porous/porous_setup, adaptive/adaptivity); this file reads the case-level keys (domain, time,
// blocks, meshes, tank, methods, validation, render, tiers) and calls the section readers.
#pragma once
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "adaptive/adaptivity.hpp"
#include "io/json_reader.hpp"
#include "io/mesh_spec.hpp"
#include "io/regression_spec.hpp"
#include "io/scene_spec.hpp"
#include "porous/porous_params.hpp"
#include "sand/sand_params.hpp"
#include "sph/equation_of_state.hpp"
#include "water/water_forces.hpp"

namespace sc {

struct TierSpec {
  std::vector<double> spacings;  ///< particle spacings [m], coarse to fine; the last one is reported
  double end_time = 0.0;         ///< [s]; 0 = the case's time.end
  /// The methods `validate --method all` runs in this tier (empty: every method the case supports).
  /// A method that fails the case's gates at this tier's spacings runs in the full tier only.
  std::vector<std::string> methods;
};

/// A convergence study of a case ("convergence"; `sandcastle validate --convergence`): the case run
/// at each of `spacings`, and for each metric of `orders` (an error against the case's reference)
/// the order the method should reach, err ∝ dx^order (validation/convergence.hpp).
struct ConvergenceSpec {
  std::vector<double> spacings;
  std::map<std::string, double> orders;
};

struct CaseSpec {
  std::string file, name, description;
  int dimension = 2;
  std::vector<double> domain_min, domain_max, gravity;
  double end_time = 1.0;        ///< [s]
  double dt_max = 0.001;        ///< [s] the fixed step (thesis default) or the cap of the CFL step
  double cfl = 0.0;             ///< Courant number; 0 = fixed step dt_max
  double frame_interval = 0.0;  ///< [s] between VTU frames in `run`; 0 = first and last only
  double relax_until = 0.0;     ///< [s] initial relaxation phase (velocity damping) ends here
  double relax_rate = 0.0;      ///< [1/s] damping rate during the relaxation
  double support_ratio = 2.0;   ///< kernel support h / particle spacing
  double density_window = 0.0;  ///< blow-up guard: |ρ/ρ0 − 1| above this stops the run; 0 = off
  EquationOfState eos;
  WaterParams water;
  /// Monaghan's α; when set, μ = α ρ0 h c / (2(D + 2)) at each spacing (h: support), so the
  /// numerical viscosity shrinks with the resolution. 0 = use water.viscosity as given.
  double artificial_viscosity = 0.0;
  SandParams sand;              ///< the "sand" section (needed by blocks of phase "sand")
  bool has_sand = false;
  std::optional<PorousParams> porous;  ///< the "porous" section (porous flow of sand and porous beds)
  std::optional<AdaptivitySpec> adaptive;  ///< the "adaptive" section (split and merge, thesis §3.6)
  std::vector<BlockSpec> blocks;
  std::vector<MeshSpec> meshes;  ///< closed OBJ meshes filled with particles (3-D only)
  std::optional<TankSpec> tank;
  json validation;              ///< checked by the observer named in it (validation/observers)
  json render;                  ///< camera, lights and filmstrip of `sandcastle render`, checked there (validation/render)
  RegressionSpec regression;    ///< limits of the comparison with the baseline
  std::string parameters_hash;  ///< of the canonical case JSON (io/regression_spec.hpp)
  std::map<std::string, TierSpec> tiers;
  std::optional<ConvergenceSpec> convergence;
  /// The method a run uses when none is asked for ("method", default "sph"; solver/method/).
  std::string method = "sph";
  /// "methods": {NAME: {...that method's own parameters...}}: the methods the case supports besides
  /// `method`, each read and checked by its method (solver/<method>/).
  json methods = json::object();
  /// Whether the case can be run by `name` (it is `method` or a key of `methods`).
  bool supports(const std::string& name) const { return name == method || methods.contains(name); }
};

/// Loads and checks a case file. Throws InputError (file, JSON path, rule) on any problem.
CaseSpec load_case(const std::string& path);

/// Loads and checks a case document already read from `path` (named in errors), e.g. one with a
/// JSON merge patch applied (validation/errata.hpp).
CaseSpec load_case(const json& doc, const std::string& path);

}  // namespace sc
