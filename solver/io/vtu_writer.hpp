// ParaView output: one VTU (VTK unstructured grid, ASCII) per frame with every particle field as
// a point array, and a PVD collection that lists the frames with their times.
#pragma once
#include <cstdint>
#include <functional>
#include <span>
#include <sstream>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/particle_set.hpp"

namespace sc {

namespace vtu_detail {
template <class T>
const char* vtk_type() {
  if constexpr (std::is_same_v<T, std::uint8_t>) return "UInt8";
  else if constexpr (std::is_same_v<T, std::int64_t>) return "Int64";
  else if constexpr (std::is_same_v<T, std::int32_t>) return "Int32";
  else return "Float64";
}
}  // namespace vtu_detail

/// The VTU document for particles at positions `x` whose point arrays `visit_fields` lists: it
/// calls its argument with (name, container) for each field, a container of numbers or of Vec<D>.
/// Every method's particles are written by this one function.
template <int D, class VisitFields>
std::string vtu_points_document(std::span<const Vec<D>> x, const VisitFields& visit_fields) {
  std::ostringstream o;
  o.precision(17);
  const std::size_t n = x.size();
  o << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
    << "<UnstructuredGrid>\n<Piece NumberOfPoints=\"" << n << "\" NumberOfCells=\"" << n << "\">\n<Points>\n"
    << "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < n; ++i) {
    for (int d = 0; d < 3; ++d) o << (d < D ? x[i][d] : 0.0) << (d < 2 ? ' ' : '\n');
  }
  o << "</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < n; ++i) o << i << '\n';
  o << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < n; ++i) o << i + 1 << '\n';
  o << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < n; ++i) o << "1\n";  // VTK_VERTEX
  o << "</DataArray>\n</Cells>\n<PointData>\n";
  visit_fields([&](std::string_view name, const auto& field) {
    using T = std::remove_cv_t<typename std::decay_t<decltype(field)>::value_type>;
    if constexpr (std::is_arithmetic_v<T>) {
      o << "<DataArray type=\"" << vtu_detail::vtk_type<T>() << "\" Name=\"" << name << "\" format=\"ascii\">\n";
      for (const auto& value : field) o << +value << '\n';
    } else {
      o << "<DataArray type=\"Float64\" Name=\"" << name << "\" NumberOfComponents=\"3\" format=\"ascii\">\n";
      for (const auto& value : field)
        for (int d = 0; d < 3; ++d) o << (d < D ? value[d] : 0.0) << (d < 2 ? ' ' : '\n');
    }
    o << "</DataArray>\n";
  });
  o << "</PointData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  return o.str();
}

/// The VTU document for the particles (every field of ParticleSet::visit_fields).
template <int D>
std::string vtu_document(const ParticleSet<D>& ps);

/// The PVD collection listing (time, relative file name) pairs; `parts(k)` names further files of
/// frame k (its surfaces), listed as parts 1, 2, ... of that time step so that ParaView plays them
/// together with the particles (part 0).
std::string pvd_document(const std::vector<std::pair<double, std::string>>& frames,
                         const std::function<std::vector<std::string>(std::size_t)>& parts = {});

}  // namespace sc
