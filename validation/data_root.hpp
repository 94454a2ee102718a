// Where the command finds what it reads besides a case file: the cases, the baselines, the
// reference data and the report scripts. One root, in this order: `--root DIR`, the environment
// variable SANDCASTLE_ROOT, the source tree the binary was built from. An installed or relocated
// binary works once the root points at a copy of the repository (or of cases/, reference/ and
// reports/).
#pragma once
#include <string>

namespace sc {

/// The root folder (no trailing slash).
const std::string& data_root();

/// Sets the root from `--root` (empty: SANDCASTLE_ROOT, else the source tree). Throws InputError
/// when the chosen folder has no cases/ subfolder, naming where the root came from.
void set_data_root(const std::string& from_flag);

/// data_root() + "/" + relative.
std::string data_path(const std::string& relative);

}  // namespace sc
