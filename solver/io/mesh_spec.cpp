#include "io/mesh_spec.hpp"

#include <algorithm>
#include <filesystem>

namespace fs = std::filesystem;

namespace sc {

namespace {

std::string resolve_mesh_file(JsonObject& o, const std::string& case_file) {
  const std::string name = o.string("file");
  const fs::path case_dir = fs::absolute(case_file).parent_path();
  const fs::path candidates[] = {case_dir / name, case_dir.parent_path().parent_path() / name};
  for (const fs::path& p : candidates)
    if (fs::is_regular_file(p)) return fs::weakly_canonical(p).string();
  o.fail("file", "mesh file not found (looked in " + candidates[0].string() + " and " + candidates[1].string() + ")");
}

}  // namespace

MeshSpec read_mesh(JsonObject o, const std::string& case_file, bool with_sand) {
  MeshSpec m;
  m.json_path = o.path();
  m.file = resolve_mesh_file(o, case_file);
  const std::string phase = o.string("phase");
  if (phase != "water" && !(phase == "sand" && with_sand))
    o.fail("phase", "must be one of the phases this case defines (water; sand needs the \"sand\" section)");
  m.phase = phase == "sand" ? Phase::Sand : Phase::Water;
  m.placement.up_axis = o.one_of("up_axis", {"y", "z"}, "z");
  if (o.has("scale") == o.has("size")) o.fail("scale", "give exactly one of \"scale\" and \"size\"");
  m.placement.scale = o.has("scale") ? o.positive("scale") : 1.0;
  m.placement.size = o.has("size") ? o.positive("size") : 0.0;
  if (o.has("translation") == o.has("min_corner")) o.fail("translation", "give exactly one of \"translation\" and \"min_corner\"");
  if (o.has("translation")) m.placement.translation = o.numbers("translation", 3);
  else m.placement.min_corner = o.numbers("min_corner", 3);
  o.finish();
  return m;
}

}  // namespace sc
