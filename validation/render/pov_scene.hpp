// The POV-Ray scene of one 3-D frame (docs/render.md): camera, lights and floor of the render
// settings, each surface a mesh2 with smooth normals, water clear and sand matte, sand darker where
// its vertices are wetter. Checked by tests/test_render.cpp (silhouette of a sphere).
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "render/render_settings.hpp"
#include "surface/surface_mesh.hpp"

namespace sc::render {

/// The scene of the surfaces of one frame, in the case's right-handed, z-up coordinates.
std::string pov_scene(const RenderSettings& settings, const std::vector<std::pair<Phase, surface::SurfaceMesh>>& surfaces);

}  // namespace sc::render
