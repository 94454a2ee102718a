#include "render/frame_series.hpp"

#include <pugixml.hpp>

#include <algorithm>
#include <sstream>

#include "core/errors.hpp"
#include "runner.hpp"

namespace sc::render {

namespace {

pugi::xml_document load_xml(const std::string& path) {
  pugi::xml_document doc;
  const pugi::xml_parse_result r = doc.load_file(path.c_str());
  if (!r) throw InputError(path, "(document)", std::string("not a readable XML file: ") + r.description());
  return doc;
}

/// The numbers of a DataArray (ASCII format).
template <class T>
std::vector<T> numbers(const pugi::xml_node& array) {
  std::istringstream in(array.child_value());
  std::vector<T> out;
  for (T v; in >> v;) out.push_back(v);
  return out;
}

/// The phase whose surface of `frame` is `file` (runner.hpp surface_file_name); false for a particle file.
bool surface_phase(const std::string& file, std::size_t frame, Phase& phase) {
  for (const Phase p : {Phase::Water, Phase::Sand})
    if (file == surface_file_name(p, frame)) {
      phase = p;
      return true;
    }
  return false;
}

}  // namespace

std::vector<Frame> read_frame_series(const std::string& run_dir) {
  const std::string path = run_dir + "/frames.pvd";
  const pugi::xml_document doc = load_xml(path);
  const pugi::xml_node collection = doc.child("VTKFile").child("Collection");
  if (!collection) throw InputError(path, "/VTKFile/Collection", "not a PVD collection of frames");
  std::vector<Frame> frames;
  for (const pugi::xml_node set : collection.children("DataSet")) {
    const std::string file = set.attribute("file").value();
    if (set.attribute("part").as_int() == 0) frames.push_back({set.attribute("timestep").as_double(), file, {}});
    else if (Phase phase; !frames.empty() && surface_phase(file, frames.size() - 1, phase))
      frames.back().surfaces.emplace_back(phase, file);
  }
  if (frames.empty()) throw InputError(path, "/VTKFile/Collection", "lists no frames");
  return frames;
}

surface::SurfaceMesh read_surface_file(const std::string& path) {
  const pugi::xml_document doc = load_xml(path);
  const pugi::xml_node piece = doc.child("VTKFile").child("PolyData").child("Piece");
  const std::vector<double> xyz = numbers<double>(piece.child("Points").child("DataArray"));
  const std::vector<std::uint32_t> corners =
      numbers<std::uint32_t>(piece.child("Polys").find_child_by_attribute("DataArray", "Name", "connectivity"));
  const std::size_t n = piece.attribute("NumberOfPoints").as_ullong();
  if (!piece || xyz.size() != 3 * n || corners.size() != 3 * piece.attribute("NumberOfPolys").as_ullong())
    throw InputError(path, "/VTKFile/PolyData/Piece", "not a triangle mesh (points and triangles do not match their counts)");
  surface::SurfaceMesh mesh;
  for (std::size_t i = 0; i < n; ++i) mesh.points.emplace_back(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
  for (std::size_t t = 0; 3 * t < corners.size(); ++t) {
    if (std::max({corners[3 * t], corners[3 * t + 1], corners[3 * t + 2]}) >= n)
      throw InputError(path, "/VTKFile/PolyData/Piece/Polys", "a triangle names a point the mesh does not have");
    mesh.triangles.push_back({corners[3 * t], corners[3 * t + 1], corners[3 * t + 2]});
  }
  mesh.saturation =
      numbers<double>(piece.child("PointData").find_child_by_attribute("DataArray", "Name", "saturation"));
  if (!mesh.saturation.empty() && mesh.saturation.size() != n)
    throw InputError(path, "/VTKFile/PolyData/Piece/PointData", "saturation does not have one value per point");
  return mesh;
}

}  // namespace sc::render
