// A run's frames as `sandcastle run` lists them in frames.pvd: per time step the particle frame
// (VTU) and the surfaces of its phases (VTP, `run --surface`), read with pugixml (Debian
// libpugixml-dev).
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "core/types.hpp"
#include "surface/surface_mesh.hpp"

namespace sc::render {

struct Frame {
  double time = 0.0;
  std::string particles;                               ///< the VTU file, relative to the run folder
  std::vector<std::pair<Phase, std::string>> surfaces;  ///< the VTP file of each phase that has one
};

/// The frames of RUN_DIR/frames.pvd in order; InputError (file, rule) when it is missing or is not
/// such a series.
std::vector<Frame> read_frame_series(const std::string& run_dir);

/// The triangle mesh of a VTP surface file (surface/surface_mesh.hpp vtp_document), with its point
/// array "saturation" when it has one; InputError when the file is not such a mesh.
surface::SurfaceMesh read_surface_file(const std::string& path);

}  // namespace sc::render
