#include "render/programs.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <sstream>
#include <thread>

extern char** environ;

namespace sc::render {

std::string find_program(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const std::filesystem::path candidate = std::filesystem::path(dir.empty() ? "." : dir) / name;
    if (::access(candidate.c_str(), X_OK) == 0 && !std::filesystem::is_directory(candidate)) return candidate.string();
  }
  return {};
}

bool run_program(const std::vector<std::string>& argv, const std::string& log) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) return false;
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return false;
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

bool run_parallel(std::size_t count, int parallel, const std::function<bool(std::size_t)>& task,
                  const std::function<void(std::size_t, bool)>& done) {
  std::atomic<std::size_t> next{0};
  std::atomic<bool> all_ok{true};
  std::mutex report;
  auto worker = [&]() {
    for (std::size_t k = next++; k < count; k = next++) {
      const bool ok = task(k);
      if (!ok) all_ok = false;
      const std::lock_guard<std::mutex> lock(report);
      done(k, ok);
    }
  };
  std::vector<std::jthread> workers;
  for (int t = 0; t < std::max(1, parallel); ++t) workers.emplace_back(worker);
  workers.clear();  // joins
  return all_ok;
}

}  // namespace sc::render
