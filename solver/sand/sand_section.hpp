// The "sand" section of a case file, read and checked (keys in cases/README.md). Like every physics
// folder, sand/ owns its section's reader; case/case_file.cpp only calls it.
#pragma once
#include "io/json_reader.hpp"
#include "sand/sand_params.hpp"

namespace sc {

/// Reads the "sand" section. Throws InputError (file, JSON path, rule) on any problem.
SandParams read_sand(JsonObject o);

}  // namespace sc
