// The `render` block of a case (docs/render.md): image size, camera, lights, floor and the frames of
// the filmstrip of `sandcastle render`, each key optional, with defaults fitted to the scene's box
// (the case's tank, else its domain).
#pragma once
#include <vector>

#include "case/case_file.hpp"
#include "core/types.hpp"

namespace sc::render {

struct Camera {
  bool orthographic = false;
  Vec<3> location, look_at;
  double angle = 40.0;       ///< perspective: horizontal field of view [degrees]
  double view_width = 1.0;   ///< orthographic: width of the view [m] (its height follows the image's aspect)
};

struct Light {
  Vec<3> position;
  Vec<3> color;  ///< linear RGB intensity
};

struct RenderSettings {
  int width = 640, height = 480;  ///< image size [pixels]
  Camera camera;
  std::vector<Light> lights;
  bool floor = true;              ///< a floor plane at the bottom of the scene's box (3-D)
  Vec<3> background{0.92, 0.95, 1.0};
  Vec<3> box_min, box_max;        ///< the scene's box (z = 0 for 2-D cases)
  std::vector<long> filmstrip;    ///< frames of the filmstrip; empty: first, middle and last
};

/// The render settings of `spec`: its "render" block read and checked (InputError naming the case
/// file, the JSON path under /render and the rule), the keys it leaves out set from the scene's box.
RenderSettings read_render_settings(const CaseSpec& spec);

}  // namespace sc::render
