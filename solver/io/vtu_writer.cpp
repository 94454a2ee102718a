#include "io/vtu_writer.hpp"

#include <sstream>

namespace sc {

template <int D>
std::string vtu_document(const ParticleSet<D>& ps) {
  return vtu_points_document<D>(std::span<const Vec<D>>(ps.x.data(), ps.size()),
                                [&](const auto& visit) { ps.visit_fields(visit); });
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
