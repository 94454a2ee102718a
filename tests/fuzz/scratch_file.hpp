// The one file a fuzz target writes each input to: under the temporary folder, named by the
// process, and removed when the fuzzer ends (libFuzzer exits normally at the end of its runs).
#pragma once
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace sc::fuzz {

class ScratchFile {
 public:
  ScratchFile(const std::string& stem, const std::string& suffix)
      : path_((std::filesystem::temp_directory_path() /
               ("sandcastle_fuzz_" + stem + "_" + std::to_string(::getpid()) + suffix)).string()) {}
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;
  ~ScratchFile() { std::remove(path_.c_str()); }

  /// Replaces the file's contents with the input's bytes; returns the path.
  const std::string& write(const std::uint8_t* data, std::size_t size) const {
    std::ofstream(path_, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    return path_;
  }

 private:
  std::string path_;
};

}  // namespace sc::fuzz
