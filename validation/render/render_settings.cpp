#include "render/render_settings.hpp"

#include <algorithm>
#include <cmath>

#include "io/json_reader.hpp"

namespace sc::render {

namespace {

Vec<3> vec3(const std::vector<double>& v) { return {v[0], v[1], v[2]}; }

/// A colour: three numbers, each at least 0.
Vec<3> read_color(JsonObject& o, const std::string& key, const Vec<3>& fallback) {
  if (!o.has(key)) return fallback;
  const Vec<3> c = vec3(o.numbers(key, 3));
  if (c.minCoeff() < 0.0) o.fail(key, "colour components must be at least 0");
  return c;
}

/// The scene's box: the tank where the case has one, else the domain; z = 0 in 2-D.
void set_box(const CaseSpec& spec, RenderSettings& s) {
  const std::vector<double>& lo = spec.tank ? spec.tank->min : spec.domain_min;
  const std::vector<double>& hi = spec.tank ? spec.tank->max : spec.domain_max;
  s.box_min.setZero();
  s.box_max.setZero();
  for (int d = 0; d < spec.dimension; ++d) {
    s.box_min[d] = lo[d];
    s.box_max[d] = hi[d];
  }
}

/// The default view: from the front (−y), to the left and above, far enough that the sphere around
/// the scene's box fills the narrower field of view.
void default_camera(const RenderSettings& s, Camera& c) {
  const Vec<3> centre = 0.5 * (s.box_min + s.box_max);
  const double radius = 0.5 * (s.box_max - s.box_min).norm();
  const double half_h = 0.5 * c.angle * pi / 180.0;
  const double half_v = std::atan(std::tan(half_h) * s.height / s.width);
  c.look_at = centre;
  c.location = centre + radius / std::sin(std::min(half_h, half_v)) * Vec<3>(-0.35, -1.0, 0.55).normalized();
  c.view_width = 2.0 * radius * std::max(1.0, static_cast<double>(s.width) / s.height);
}

void read_camera(JsonObject o, RenderSettings& s) {
  Camera& c = s.camera;
  c.orthographic = o.one_of("projection", {"perspective", "orthographic"}, "perspective") == "orthographic";
  c.angle = o.in_range("angle", 0.0, 180.0, true, c.angle);
  default_camera(s, c);
  if (o.has("location")) c.location = vec3(o.numbers("location", 3));
  if (o.has("look_at")) c.look_at = vec3(o.numbers("look_at", 3));
  c.view_width = o.positive("view_width", c.view_width);
  const Vec<3> view = c.look_at - c.location;
  if (view.norm() == 0.0) o.fail("look_at", "must differ from the camera's location");
  if (std::abs(view.normalized()[2]) > 0.999) o.fail("look_at", "the view must not be straight along z (z is up in the picture)");
  o.finish();
}

/// Default lights: a key light above, in front and to the left of the scene, and a weaker fill
/// light from the right.
std::vector<Light> default_lights(const RenderSettings& s) {
  const Vec<3> centre = 0.5 * (s.box_min + s.box_max);
  const double reach = 4.0 * (s.box_max - s.box_min).norm();
  return {{centre + reach * Vec<3>(-0.5, -1.0, 1.5).normalized(), Vec<3>(1.0, 1.0, 1.0)},
          {centre + reach * Vec<3>(1.0, -0.6, 0.4).normalized(), Vec<3>(0.35, 0.35, 0.4)}};
}

std::vector<long> read_filmstrip(JsonObject& o) {
  const json& list = o.raw("filmstrip");
  if (!list.is_array() || list.empty()) o.fail("filmstrip", "must be a non-empty array of frame numbers");
  std::vector<long> frames;
  for (const json& f : list) {
    if (!f.is_number_integer() || f.get<long>() < 0) o.fail("filmstrip", "frame numbers must be integers >= 0");
    frames.push_back(f.get<long>());
  }
  return frames;
}

}  // namespace

RenderSettings read_render_settings(const CaseSpec& spec) {
  JsonObject o(spec.render, "/render", spec.file);
  RenderSettings s;
  s.width = static_cast<int>(o.integer("width", 16, 8192, s.width));
  s.height = static_cast<int>(o.integer("height", 16, 8192, s.height));
  set_box(spec, s);
  if (o.has("camera")) read_camera(o.object("camera"), s);
  else default_camera(s, s.camera);
  s.lights = default_lights(s);
  if (o.has("lights")) {
    s.lights.clear();
    for (JsonObject l : o.objects("lights")) {  // an empty list leaves the ambient light only
      s.lights.push_back({vec3(l.numbers("position", 3)), read_color(l, "color", Vec<3>(1.0, 1.0, 1.0))});
      l.finish();
    }
  }
  s.floor = o.boolean("floor", s.floor);
  s.background = read_color(o, "background", s.background);
  if (o.has("filmstrip")) s.filmstrip = read_filmstrip(o);
  o.finish();
  return s;
}

}  // namespace sc::render
