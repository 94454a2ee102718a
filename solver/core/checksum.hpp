// The state hash every method reports (Method::checksum): FNV-1a 64 over the bytes of all
// positions and velocities in index order, as 16 hex digits. Two runs agree bitwise exactly when
// their checksums do.
#pragma once
#include <cstdint>
#include <cstdio>
#include <span>
#include <string>

#include "core/types.hpp"

namespace sc {

template <int D>
std::string state_checksum(std::span<const Vec<D>> x, std::span<const Vec<D>> v) {
  std::uint64_t hash = 1469598103934665603ull;
  auto mix = [&hash](const void* data, std::size_t bytes) {
    const auto* c = static_cast<const unsigned char*>(data);
    for (std::size_t k = 0; k < bytes; ++k) {
      hash ^= c[k];
      hash *= 1099511628211ull;
    }
  };
  for (std::size_t i = 0; i < x.size(); ++i) {
    mix(x[i].data(), sizeof(double) * D);
    mix(v[i].data(), sizeof(double) * D);
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(hash));
  return buf;
}

}  // namespace sc
