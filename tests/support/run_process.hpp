#pragma once
// Runs a program to completion with its stdout and stderr captured, for testing the
// command-line fronts as a user runs them.

#include <chrono>
#include <string>
#include <vector>

namespace subfeed::testing {

struct ProcessResult {
  int exit_code = -1; // -1 when killed by a signal
  std::string out;
  std::string err;
};

[[nodiscard]] ProcessResult run_process(const std::vector<std::string>& argv);

} // namespace subfeed::testing

namespace subfeed::testing {

// A program running beside the test (a simulator, or a sender to interrupt). Killed with
// SIGKILL if still running when destroyed.
class BackgroundProcess {
public:
  // `stdin_path` is opened as the program's standard input (a pty slave makes it a terminal);
  // `stderr_path`, when given, as its standard error (wait() then reports none).
  explicit BackgroundProcess(const std::vector<std::string>& argv,
                             const std::string& stdin_path = "/dev/null",
                             const std::string& stderr_path = {});
  BackgroundProcess(const BackgroundProcess&) = delete;
  BackgroundProcess& operator=(const BackgroundProcess&) = delete;
  ~BackgroundProcess();

  // The first line the program printed on stdout (waits up to 5 s; empty if none).
  std::string first_line();
  void signal(int number) const;
  // Waits for the program to end; its exit code (-1 if killed) and everything it printed.
  ProcessResult wait();

private:
  int pid_ = -1;
  int out_fd_ = -1;
  std::string out_;
  std::string err_file_;
  bool waited_ = false;
  ProcessResult result_;
};

} // namespace subfeed::testing
