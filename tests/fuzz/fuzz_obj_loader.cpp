// libFuzzer target: the OBJ mesh loader (load_obj, require_closed, signed_volume) on arbitrary
// bytes. A mesh or an InputError is fine; anything else is a bug. Run by tools/fuzz.sh.
#include <cstdint>

#include "core/errors.hpp"
#include "geometry/triangle_mesh.hpp"
#include "scratch_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const sc::fuzz::ScratchFile file("mesh", ".obj");
  const std::string& path = file.write(data, size);
  try {
    const sc::TriangleMesh mesh = sc::load_obj(path);
    sc::require_closed(mesh, path);
    static_cast<void>(mesh.signed_volume());
  } catch (const sc::InputError&) {
  }
  return 0;
}
