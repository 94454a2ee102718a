// libFuzzer target: the case loader (load_case) on arbitrary bytes. A loaded case or an
// InputError is fine; anything else (another exception, a crash, a sanitizer report, a hang) is a
// bug. Built by -DSANDCASTLE_FUZZ=ON with clang, run by tools/fuzz.sh.
#include <cstdint>

#include "case/case_file.hpp"
#include "scratch_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const sc::fuzz::ScratchFile file("case", ".json");
  const std::string& path = file.write(data, size);
  try {
    sc::load_case(path);
  } catch (const sc::InputError&) {
  }
  return 0;
}
