// libFuzzer target: the case loader (load_case) on arbitrary bytes. A loaded case or an
// InputError is fine; anything else (another exception, a crash, a sanitizer report, a hang) is a
// bug. Built by -DSANDCASTLE_FUZZ=ON with clang, run by tools/fuzz.sh.
#include <unistd.h>

#include <cstdint>
#include <fstream>

#include "case/case_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = "/tmp/sandcastle_fuzz_case_" + std::to_string(::getpid()) + ".json";
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  try {
    sc::load_case(path);
  } catch (const sc::InputError&) {
  }
  return 0;
}
