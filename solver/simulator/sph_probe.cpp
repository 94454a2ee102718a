#include "simulator/sph_probe.hpp"

#include <stdexcept>

#include "simulator/sph_method.hpp"

namespace sc {

void require_sph(const CaseSpec& spec, std::string_view who) {
  if (spec.method != "sph")
    throw InputError(spec.file, "/method", std::string(who) + " needs the SPH method (\"sph\"); this run uses \"" +
                                               spec.method + "\"");
}

template <int D>
const ParticleSet<D>& SphProbe<D>::particles() const {
  return method_.state();
}

template <int D>
const NeighbourGrid<D>& SphProbe<D>::neighbours() const {
  return method_.simulator().neighbours();
}

template <int D>
double SphProbe<D>::full_water_mass() const {
  if (!method_.simulator().params().porous) throw std::logic_error("full_water_mass: the case has no \"porous\" section");
  return method_.simulator().params().porous->water_mass;
}

template <int D>
const AdaptAccount& SphProbe<D>::adapt_account() const {
  return method_.simulator().adapt_account();
}

template <int D>
std::optional<DecompositionAccount> SphProbe<D>::decomposition() const {
  if (!method_.simulator().decomposition()) return std::nullopt;
  DecompositionAccount a = method_.simulator().decomposition()->totals();
  a.clusters_across_ranks = method_.simulator().clusters_across_ranks();  // the same on every rank
  return a;
}

template <int D>
SphProbe<D> require_sph(const Method<D>& method, std::string_view who) {
  const auto* sph = dynamic_cast<const SphMethod<D>*>(&method);
  if (!sph) throw std::logic_error(std::string(who) + " needs the SPH method; this run uses \"" + std::string(method.name()) + "\"");
  return SphProbe<D>(*sph);
}

template class SphProbe<2>;
template class SphProbe<3>;
template SphProbe<2> require_sph<2>(const Method<2>&, std::string_view);
template SphProbe<3> require_sph<3>(const Method<3>&, std::string_view);

}  // namespace sc
