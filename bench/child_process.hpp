#pragma once
// A program run in a child process of its own, as a user runs it: its wall time, its own peak
// resident memory (wait4's ru_maxrss, apart from the bench's), its exit, and what it printed.

#include <chrono>
#include <csignal>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <spawn.h>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

extern char** environ;

namespace subfeed::bench {

struct Child {
  double seconds = 0.0;
  double peak_mib = 0.0;
  bool started = false;
  bool timed_out = false; // killed at the time limit
  int exit_code = -1;     // -1 when it did not exit by itself
  std::string out, err;
};

inline std::string slurp(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Runs `argv` (argv[0] a path), its output to files in `dir`; killed after `limit_s` seconds
// (0: no limit).
inline Child run_child(std::vector<std::string> argv_text, const std::filesystem::path& dir,
                       double limit_s = 0.0) {
  const auto out = dir / "child-stdout.txt", err = dir / "child-stderr.txt";
  std::vector<char*> argv;
  for (auto& a : argv_text) {
    argv.push_back(a.data());
  }
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  Child child;
  const auto start = std::chrono::steady_clock::now();
  pid_t pid = 0;
  child.started = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ) == 0;
  posix_spawn_file_actions_destroy(&actions);
  if (!child.started) {
    return child;
  }
  const auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  int status = 0;
  rusage usage{};
  while (::wait4(pid, &status, limit_s > 0.0 ? WNOHANG : 0, &usage) == 0) {
    if (elapsed() > limit_s) {
      ::kill(pid, SIGKILL);
      child.timed_out = true;
      ::wait4(pid, &status, 0, &usage);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  child.seconds = elapsed();
  child.peak_mib = static_cast<double>(usage.ru_maxrss) / 1024.0;
  child.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  child.out = slurp(out);
  child.err = slurp(err);
  return child;
}

} // namespace subfeed::bench
