#include "render/pov_scene.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace sc::render {

namespace {

/// Shades of sand from dry (index 0) to saturated (the last): a vertex takes the shade nearest its
/// saturation and POV-Ray blends the shades of a triangle's corners.
constexpr int kSandShades = 11;

std::ostream& operator<<(std::ostream& o, const Vec<3>& v) { return o << '<' << v[0] << ',' << v[1] << ',' << v[2] << '>'; }

void write_camera(std::ostream& o, const RenderSettings& s) {
  const Camera& c = s.camera;
  const double aspect = static_cast<double>(s.width) / s.height;
  // right = −x: POV-Ray is left-handed; a negative right vector makes it right-handed, sky z keeps z up.
  if (c.orthographic)
    o << "camera { orthographic location " << c.location << " sky <0,0,1> up <0,0," << c.view_width / aspect
      << "> right <" << -c.view_width << ",0,0> look_at " << c.look_at << " }\n";
  else
    o << "camera { perspective location " << c.location << " sky <0,0,1> up <0,0,1> right <" << -aspect
      << ",0,0> angle " << c.angle << " look_at " << c.look_at << " }\n";
}

/// max_trace_level 5: a ray into a splash crosses many sheets of water, each spawning a reflected and
/// a refracted ray; deeper tracing multiplies the time for little visible change.
void write_environment(std::ostream& o, const RenderSettings& s) {
  o << "#version 3.7;\nglobal_settings { assumed_gamma 1.0 max_trace_level 5 ambient_light <1,1,1> }\n"
    << "background { color rgb " << s.background << " }\n";
  write_camera(o, s);
  for (const Light& l : s.lights) o << "light_source { " << l.position << " color rgb " << l.color << " }\n";
  if (s.floor)
    o << "plane { <0,0,1>, " << s.box_min[2]
      << " pigment { color rgb <0.62,0.62,0.6> } finish { ambient 0.15 diffuse 0.7 } }\n";
}

/// Per vertex the area-weighted mean of its triangles' normals (outward, the meshes' orientation).
std::vector<Vec<3>> vertex_normals(const surface::SurfaceMesh& mesh) {
  std::vector<Vec<3>> n(mesh.points.size(), Vec<3>::Zero());
  for (const auto& t : mesh.triangles) {
    const Vec<3> a = mesh.points[t[1]] - mesh.points[t[0]], b = mesh.points[t[2]] - mesh.points[t[0]];
    const Vec<3> face = a.cross(b);
    for (const std::uint32_t v : t) n[v] += face;
  }
  for (Vec<3>& v : n) v = v.norm() > 0.0 ? Vec<3>(v.normalized()) : Vec<3>(0.0, 0.0, 1.0);
  return n;
}

std::string sand_texture(double wetness) {
  const Vec<3> dry(0.80, 0.66, 0.44), wet(0.42, 0.32, 0.19);
  std::ostringstream o;
  o << "texture { pigment { color rgb " << Vec<3>((1.0 - wetness) * dry + wetness * wet)
    << " } finish { ambient 0.12 diffuse 0.8 specular 0.05 } }";
  return o.str();
}

const char* kWaterTexture =
    "texture { pigment { color rgbf <0.55,0.72,0.95,0.75> } finish { ambient 0.05 diffuse 0.25 specular 0.7 "
    "roughness 0.003 reflection 0.06 } }";

int shade(double saturation) { return static_cast<int>(std::lround(std::clamp(saturation, 0.0, 1.0) * (kSandShades - 1))); }

void write_mesh(std::ostream& o, Phase phase, const surface::SurfaceMesh& mesh) {
  if (mesh.triangles.empty()) return;
  const bool shaded = phase == Phase::Sand && !mesh.saturation.empty();
  o << "mesh2 {\nvertex_vectors { " << mesh.points.size();
  for (const Vec<3>& p : mesh.points) o << ",\n" << p;
  o << " }\nnormal_vectors { " << mesh.points.size();
  for (const Vec<3>& n : vertex_normals(mesh)) o << ",\n" << n;
  o << " }\n";
  if (shaded) {
    o << "texture_list { " << kSandShades;
    for (int k = 0; k < kSandShades; ++k) o << ",\n" << sand_texture(static_cast<double>(k) / (kSandShades - 1));
    o << " }\n";
  }
  o << "face_indices { " << mesh.triangles.size();
  for (const auto& t : mesh.triangles) {
    o << ",\n<" << t[0] << ',' << t[1] << ',' << t[2] << '>';
    if (shaded)
      for (const std::uint32_t v : t) o << ',' << shade(mesh.saturation[v]);
  }
  o << " }\ninside_vector <0,0,1>\n";
  if (phase == Phase::Water) o << kWaterTexture << "\ninterior { ior 1.33 }\n";
  else if (!shaded) o << sand_texture(0.0) << '\n';
  o << "}\n";
}

}  // namespace

std::string pov_scene(const RenderSettings& settings, const std::vector<std::pair<Phase, surface::SurfaceMesh>>& surfaces) {
  std::ostringstream o;
  o.precision(9);
  write_environment(o, settings);
  for (const auto& [phase, mesh] : surfaces) write_mesh(o, phase, mesh);
  return o.str();
}

}  // namespace sc::render
