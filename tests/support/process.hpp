// Runs the real `sandcastle` command (SANDCASTLE_BINARY, set by CMake) as a child process, for the
// tests that check it end to end: exit code, signal, stdout and stderr, with a timeout after which
// the child is killed and the result marked as timed out (a hang is a failure, not a stuck CI).
#pragma once
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace sc::test {

struct ProcessResult {
  int exit_code = -1;  ///< exit status; -1 if a signal ended the process
  int signal = 0;      ///< the signal that ended it, 0 if it exited
  bool timed_out = false;
  std::string out, err;
};

/// The paths fresh_path gave out, removed with everything in them when the test process ends, so
/// that a run of the tests leaves nothing behind in the temporary folder. With
/// SANDCASTLE_KEEP_TEST_FILES set (to anything) they stay, to look at a failing test's output.
class ScratchPaths {
 public:
  ScratchPaths() = default;
  ScratchPaths(const ScratchPaths&) = delete;
  ScratchPaths& operator=(const ScratchPaths&) = delete;
  ~ScratchPaths() {
    if (std::getenv("SANDCASTLE_KEEP_TEST_FILES")) return;
    std::error_code ignored;  // a path never created, or already removed by its test
    for (const auto& p : paths_) std::filesystem::remove_all(p, ignored);
  }
  void add(const std::filesystem::path& p) { paths_.push_back(p); }

 private:
  std::vector<std::filesystem::path> paths_;
};

inline ScratchPaths& scratch_paths() {
  static ScratchPaths paths;  // one per process, whichever test file asks first
  return paths;
}

/// A fresh, unused path under the temporary folder, ending in `suffix` (e.g. ".json"); nothing is
/// created, and whatever a test puts there is removed when the process ends (ScratchPaths).
inline std::string fresh_path(const std::string& stem, const std::string& suffix = "") {
  static int counter = 0;
  const auto p = std::filesystem::temp_directory_path() /
                 ("sandcastle_" + stem + "_" + std::to_string(::getpid()) + "_" + std::to_string(counter++) + suffix);
  std::filesystem::remove_all(p);
  scratch_paths().add(p);
  return p.string();
}

inline std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream buf;
  buf << in.rdbuf();
  return buf.str();
}

/// A running `program args...` (default: sandcastle) with `env` ("NAME=value") added to the environment.
class Child {
 public:
  Child(const std::vector<std::string>& args, const std::vector<std::string>& env,
        std::string program = SANDCASTLE_BINARY)
      : program_(std::move(program)), out_(fresh_path("stdout")), err_(fresh_path("stderr")) {
    std::fflush(nullptr);  // else the child's freopen flushes the parent's pending output a second time
    pid_ = ::fork();
    if (pid_ == 0) exec(args, env);
  }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;
  ~Child() {
    if (!reaped_) kill(SIGKILL), wait(0.0);
    std::filesystem::remove(out_);
    std::filesystem::remove(err_);
  }

  void kill(int sig) const { ::kill(pid_, sig); }

  /// Waits until the child ends or `timeout` seconds pass (then kills it; timeout 0: wait forever).
  ProcessResult wait(double timeout) {
    ProcessResult r;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout);
    int status = 0;
    while (::waitpid(pid_, &status, WNOHANG) == 0) {
      if (timeout > 0.0 && std::chrono::steady_clock::now() > deadline) {
        r.timed_out = true;
        ::kill(pid_, SIGKILL);
        ::waitpid(pid_, &status, 0);
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    reaped_ = true;
    if (WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) r.signal = WTERMSIG(status);
    r.out = read_text(out_);
    r.err = read_text(err_);
    return r;
  }

 private:
  [[noreturn]] void exec(const std::vector<std::string>& args, const std::vector<std::string>& env) const {
    for (const std::string& e : env) ::putenv(const_cast<char*>(e.c_str()));
    if (!std::freopen(out_.c_str(), "w", stdout) || !std::freopen(err_.c_str(), "w", stderr)) ::_exit(126);
    std::vector<char*> argv{const_cast<char*>(program_.c_str())};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(program_.c_str(), argv.data());
    ::_exit(127);
  }

  std::string program_;
  pid_t pid_ = -1;
  bool reaped_ = false;
  std::string out_, err_;
};

/// Runs `sandcastle args...` to completion (killed after `timeout` s); one OpenMP thread unless
/// `env` says otherwise (the tests compare results, and a loaded machine makes spinning threads slow).
inline ProcessResult run_sandcastle(const std::vector<std::string>& args, double timeout = 120.0,
                                    std::vector<std::string> env = {"OMP_NUM_THREADS=1"}) {
  Child child(args, env);
  return child.wait(timeout);
}

/// The state checksum `sandcastle run` prints ("checksum <16 hex digits>"), or "" if none.
inline std::string printed_checksum(const std::string& out) {
  const auto k = out.find("checksum ");
  return k == std::string::npos ? std::string() : out.substr(k + 9, 16);
}

}  // namespace sc::test
