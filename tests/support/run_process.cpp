#include "support/run_process.hpp"

#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <spawn.h>
#include <sstream>
#include <stdexcept>
#include <sys/wait.h>

namespace subfeed::testing {

namespace {

std::string slurp(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

} // namespace

ProcessResult run_process(const std::vector<std::string>& argv) {
  BackgroundProcess process(argv);
  return process.wait();
}

} // namespace subfeed::testing

#include <csignal>
#include <poll.h>
#include <unistd.h>

namespace subfeed::testing {

BackgroundProcess::BackgroundProcess(const std::vector<std::string>& argv,
                                     const std::string& stdin_path,
                                     const std::string& stderr_path) {
  int pipe_fds[2];
  if (::pipe(pipe_fds) != 0) {
    throw std::runtime_error("pipe failed");
  }
  char pattern[] = "/tmp/subfeed-stderr-XXXXXX";
  const int err_fd = ::mkstemp(pattern);
  err_file_ = pattern;
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, stdin_path.c_str(), O_RDWR, 0);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], 1);
  if (stderr_path.empty()) {
    posix_spawn_file_actions_adddup2(&actions, err_fd, 2);
  } else {
    posix_spawn_file_actions_addopen(&actions, 2, stderr_path.c_str(), O_RDWR, 0);
  }
  posix_spawn_file_actions_addclose(&actions, pipe_fds[0]);
  std::vector<char*> args;
  for (const auto& a : argv) {
    args.push_back(const_cast<char*>(a.c_str()));
  }
  args.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(pipe_fds[1]);
  ::close(err_fd);
  if (spawned != 0) {
    throw std::runtime_error("cannot start " + argv.at(0));
  }
  pid_ = pid;
  out_fd_ = pipe_fds[0];
}

BackgroundProcess::~BackgroundProcess() {
  if (!waited_) {
    ::kill(pid_, SIGKILL);
    (void)wait();
  }
  ::unlink(err_file_.c_str());
}

std::string BackgroundProcess::first_line() {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (out_.find('\n') == std::string::npos && std::chrono::steady_clock::now() < deadline) {
    pollfd p{out_fd_, POLLIN, 0};
    if (::poll(&p, 1, 100) > 0) {
      char buffer[256];
      const ssize_t n = ::read(out_fd_, buffer, sizeof buffer);
      if (n <= 0) {
        break;
      }
      out_.append(buffer, static_cast<std::size_t>(n));
    }
  }
  const auto end = out_.find('\n');
  return end == std::string::npos ? std::string() : out_.substr(0, end);
}

void BackgroundProcess::signal(int number) const {
  ::kill(pid_, number);
}

ProcessResult BackgroundProcess::wait() {
  if (waited_) {
    return result_;
  }
  // Drain stdout before reaping: a child that fills the pipe would otherwise never exit.
  char buffer[4096];
  ssize_t n = 0;
  while ((n = ::read(out_fd_, buffer, sizeof buffer)) > 0) {
    out_.append(buffer, static_cast<std::size_t>(n));
  }
  ::close(out_fd_);
  int status = 0;
  ::waitpid(pid_, &status, 0);
  waited_ = true;
  result_.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result_.out = out_;
  result_.err = slurp(err_file_);
  return result_;
}

} // namespace subfeed::testing
