// Crash-safe file output: write to a temporary name in the same folder, then rename, so a run
// killed at any moment leaves only complete files.
#pragma once
#include <string>

namespace sc {

/// Writes `content` to `path` atomically (temporary file + rename). Throws std::runtime_error on
/// an I/O failure, leaving any previous file at `path` untouched.
void write_file_atomic(const std::string& path, const std::string& content);

}  // namespace sc
