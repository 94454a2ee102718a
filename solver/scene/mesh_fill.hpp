// Particles filling the meshes of a case (the "meshes" list, cases/README.md).
#pragma once
#include "case/case_file.hpp"

namespace sc {

/// Lattice points at spacing dx inside the placed mesh (winding-number test). Throws InputError
/// naming the case file and the mesh's JSON path when the mesh cannot be read, is not closed, or
/// does not fit in the domain (or inside the tank on its closed sides).
std::vector<Vec<3>, Eigen::aligned_allocator<Vec<3>>> mesh_particles(const CaseSpec& spec, const MeshSpec& mesh, double dx);

}  // namespace sc
