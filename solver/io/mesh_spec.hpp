// The "meshes" list of a case file: closed OBJ meshes filled with particles of one phase.
#pragma once
#include <string>

#include "core/types.hpp"
#include "io/json_reader.hpp"

namespace sc {

/// How a mesh is put into a scene: rotated so that `up_axis` of the file ("y" or "z") becomes +z,
/// scaled about the file's origin by `scale` (or so that its largest extent is `size` metres when
/// size > 0), then moved by `translation` [m], or so that its bounding-box minimum lands on
/// `min_corner` when that is given.
struct MeshPlacement {
  std::string up_axis = "z";
  double scale = 1.0;
  double size = 0.0;
  std::vector<double> translation;
  std::vector<double> min_corner;
};

struct MeshSpec {
  std::string file;       ///< resolved path of the OBJ file
  std::string json_path;  ///< e.g. /meshes/0, for error messages
  Phase phase = Phase::Water;  ///< water or sand
  MeshPlacement placement;
};

/// Reads one entry {file, phase, up_axis, scale | size, translation | min_corner}. `file` is
/// looked up relative to the case's folder, then to the repository (the folder holding cases/).
/// `with_sand`: the case has a "sand" section, so "sand" is a phase a mesh may have.
MeshSpec read_mesh(JsonObject o, const std::string& case_file, bool with_sand);

}  // namespace sc
