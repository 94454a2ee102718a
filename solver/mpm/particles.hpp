// The particles of two-grid MPM: sand and water in one structure of arrays, each particle carrying
// its phase; the sand's state (elastic deformation gradient, volume correction, saturation) and the
// water's (volume ratio J, the porosity it moves through) sit in the same arrays, unused entries at
// their neutral values.
#pragma once
#include <cstdint>
#include <vector>

#include "core/types.hpp"

namespace sc::mpm {

template <int D>
struct Particles {
  std::vector<Vec<D>> x, v;         ///< position [m], velocity [m/s]
  std::vector<Mat<D>> C;            ///< APIC affine velocity [1/s]
  std::vector<Mat<D>> Fe;           ///< elastic deformation gradient F^E (sand; 𝟙 for water)
  std::vector<double> m, V0;        ///< mass [kg], volume at the start [m^D]
  std::vector<double> J;            ///< volume ratio, V = J V0 (sand: det F; water: its own volume, see porosity)
  std::vector<double> vc;           ///< volume correction v_c (sand) [-]
  std::vector<double> saturation;   ///< water fraction of the sand's pores, in [0, 1] (sand; 0 for water)
  /// The porosity n at a water particle (1 in open water): its water volume J V0 fills the mixture
  /// volume J V0 / n. The pores it is seeded in until the first grid-to-particle transfer, the
  /// grid's porosity at the particle from then on (water; 1 for sand).
  std::vector<double> porosity;
  /// The water's pressure [Pa]: a water particle's own at J; around a sand particle, the pore
  /// pressure Σ_i w_ip p_i of the last grid-to-particle transfer.
  std::vector<double> pressure;
  std::vector<std::uint8_t> phase;  ///< Phase as an integer (Water or Sand)
  /// An external force on the particle [N], constant in time: its share of a load on the material's
  /// surface (a traction t on the particle's face dx^(D−1) gives t dx^(D−1)). Zero unless set.
  std::vector<Vec<D>> load;

  std::size_t size() const { return x.size(); }
  bool is_sand(std::size_t i) const { return phase[i] == static_cast<std::uint8_t>(Phase::Sand); }
  /// Appends a particle at rest, undeformed, dry; water in pores of porosity n (1: open water).
  void add(const Vec<D>& position, double mass, double volume, Phase ph, double n = 1.0) {
    x.push_back(position);
    v.push_back(Vec<D>::Zero());
    C.push_back(Mat<D>::Zero());
    Fe.push_back(Mat<D>::Identity());
    m.push_back(mass);
    V0.push_back(volume);
    J.push_back(1.0);
    vc.push_back(0.0);
    saturation.push_back(0.0);
    porosity.push_back(n);
    pressure.push_back(0.0);
    phase.push_back(static_cast<std::uint8_t>(ph));
    load.push_back(Vec<D>::Zero());
  }
};

}  // namespace sc::mpm
