// libFuzzer target: the OBJ mesh loader (load_obj, require_closed, signed_volume) on arbitrary
// bytes. A mesh or an InputError is fine; anything else is a bug. Run by tools/fuzz.sh.
#include <unistd.h>

#include <cstdint>
#include <fstream>

#include "core/errors.hpp"
#include "geometry/triangle_mesh.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = "/tmp/sandcastle_fuzz_mesh_" + std::to_string(::getpid()) + ".obj";
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  try {
    const sc::TriangleMesh mesh = sc::load_obj(path);
    sc::require_closed(mesh, path);
    static_cast<void>(mesh.signed_volume());
  } catch (const sc::InputError&) {
  }
  return 0;
}
