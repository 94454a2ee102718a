// The programs `sandcastle render` runs (povray, ffmpeg): found on PATH, run without a shell with
// their output in a log file, several at a time.
#pragma once
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace sc::render {

/// The path of the executable `name` on PATH; empty when there is none.
std::string find_program(const std::string& name);

/// Runs argv[0] (a path) with its arguments, its standard output and error appended to `log`;
/// true when it exits with status 0.
bool run_program(const std::vector<std::string>& argv, const std::string& log);

/// Calls task(k) for k = 0 .. count − 1 on `parallel` threads, then done(k, its result) one call at
/// a time as each finishes; returns whether every task succeeded.
bool run_parallel(std::size_t count, int parallel, const std::function<bool(std::size_t)>& task,
                  const std::function<void(std::size_t, bool)>& done);

}  // namespace sc::render
