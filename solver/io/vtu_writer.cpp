#include "io/vtu_writer.hpp"

#include <sstream>
#include <type_traits>

namespace sc {

namespace {

template <class T>
const char* vtk_type() {
  if constexpr (std::is_same_v<T, double>) return "Float64";
  else if constexpr (std::is_same_v<T, std::uint8_t>) return "UInt8";
  else if constexpr (std::is_same_v<T, std::int64_t>) return "Int64";
  else if constexpr (std::is_same_v<T, std::int32_t>) return "Int32";
  else return "Float64";
}

}  // namespace

template <int D>
std::string vtu_document(const ParticleSet<D>& ps) {
  std::ostringstream o;
  o.precision(17);
  const std::size_t n = ps.size();
  o << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
    << "<UnstructuredGrid>\n<Piece NumberOfPoints=\"" << n << "\" NumberOfCells=\"" << n << "\">\n<Points>\n"
    << "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < n; ++i) {
    for (int d = 0; d < 3; ++d) o << (d < D ? ps.x[i][d] : 0.0) << (d < 2 ? ' ' : '\n');
  }
  o << "</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < n; ++i) o << i << '\n';
  o << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < n; ++i) o << i + 1 << '\n';
  o << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  for (std::size_t i = 0; i < n; ++i) o << "1\n";  // VTK_VERTEX
  o << "</DataArray>\n</Cells>\n<PointData>\n";
  ps.visit_fields([&](std::string_view name, const auto& field) {
    using T = typename std::decay_t<decltype(field)>::value_type;
    if constexpr (std::is_arithmetic_v<T>) {
      o << "<DataArray type=\"" << vtk_type<T>() << "\" Name=\"" << name << "\" format=\"ascii\">\n";
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

std::string pvd_document(const std::vector<std::pair<double, std::string>>& frames) {
  std::ostringstream o;
  o.precision(10);
  o << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
  for (const auto& [t, file] : frames) o << "<DataSet timestep=\"" << t << "\" file=\"" << file << "\"/>\n";
  o << "</Collection>\n</VTKFile>\n";
  return o.str();
}

template std::string vtu_document<2>(const ParticleSet<2>&);
template std::string vtu_document<3>(const ParticleSet<3>&);

}  // namespace sc
