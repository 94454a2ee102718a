// ParaView output: one VTU (VTK unstructured grid, ASCII) per frame with every particle field as
// a point array, and a PVD collection that lists the frames with their times.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "core/particle_set.hpp"

namespace sc {

/// The VTU document for the particles (every field of ParticleSet::visit_fields).
template <int D>
std::string vtu_document(const ParticleSet<D>& ps);

/// The PVD collection listing (time, relative file name) pairs.
std::string pvd_document(const std::vector<std::pair<double, std::string>>& frames);

}  // namespace sc
