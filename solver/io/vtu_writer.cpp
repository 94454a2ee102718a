#include "io/vtu_writer.hpp"

#include <sstream>

namespace sc {

template <int D>
std::string vtu_document(const ParticleSet<D>& ps) {
  return vtu_points_document<D>(std::span<const Vec<D>>(ps.x.data(), ps.size()),
                                [&](const auto& visit) { ps.visit_fields(visit); });
}

std::string pvd_document(const std::vector<std::pair<double, std::string>>& frames,
                         const std::function<std::vector<std::string>(std::size_t)>& parts) {
  std::ostringstream o;
  o.precision(10);
  o << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const std::vector<std::string> more = parts ? parts(k) : std::vector<std::string>{};
    o << "<DataSet timestep=\"" << frames[k].first << "\"" << (more.empty() ? "" : " part=\"0\"") << " file=\""
      << frames[k].second << "\"/>\n";
    for (std::size_t p = 0; p < more.size(); ++p)
      o << "<DataSet timestep=\"" << frames[k].first << "\" part=\"" << p + 1 << "\" file=\"" << more[p] << "\"/>\n";
  }
  o << "</Collection>\n</VTKFile>\n";
  return o.str();
}

template std::string vtu_document<2>(const ParticleSet<2>&);
template std::string vtu_document<3>(const ParticleSet<3>&);

}  // namespace sc
