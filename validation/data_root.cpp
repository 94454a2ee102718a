#include "data_root.hpp"

#include <cstdlib>
#include <filesystem>

#include "core/errors.hpp"

namespace sc {

namespace {

std::string& root() {
  static std::string value = SANDCASTLE_SOURCE_DIR;
  return value;
}

}  // namespace

const std::string& data_root() { return root(); }

void set_data_root(const std::string& from_flag) {
  const char* env = std::getenv("SANDCASTLE_ROOT");
  std::string chosen = SANDCASTLE_SOURCE_DIR, origin = "the source tree of this build";
  if (!from_flag.empty()) {
    chosen = from_flag;
    origin = "--root";
  } else if (env && *env) {
    chosen = env;
    origin = "SANDCASTLE_ROOT";
  }
  while (chosen.size() > 1 && chosen.back() == '/') chosen.pop_back();
  if (!std::filesystem::is_directory(std::filesystem::path(chosen) / "cases"))
    throw InputError(chosen, "", "the data root (from " + origin + ") has no cases/ folder: point --root or "
                                 "SANDCASTLE_ROOT at a copy of the repository");
  root() = chosen;
}

std::string data_path(const std::string& relative) { return data_root() + "/" + relative; }

}  // namespace sc
