// The "meshes" list of a case file: closed OBJ meshes filled with particles of one phase.
#pragma once
#include <string>

#include "geometry/triangle_mesh.hpp"
#include "io/json_reader.hpp"

namespace sc {

struct MeshSpec {
  std::string file;       ///< resolved path of the OBJ file
  std::string json_path;  ///< e.g. /meshes/0, for error messages
  std::string phase;      ///< "water" or "sand"
  MeshPlacement placement;
};

/// Reads one entry {file, phase, up_axis, scale | size, translation | min_corner}. `file` is
/// looked up relative to the case's folder, then to the repository (the folder holding cases/).
/// `phases` lists the phases the case allows.
MeshSpec read_mesh(JsonObject o, const std::string& case_file, const std::vector<std::string>& phases);

}  // namespace sc
