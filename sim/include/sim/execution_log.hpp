#pragma once
// The lines a simulated controller has carried out, appended to a file in order: a motion
// line once its move has ended, any other line once the moves queued before it have ended
// (its effect is modal: it takes place in sequence). A controller that dies or resets leaves
// out what had not run yet, so the file tells exactly what the machine did.

#include <cstddef>
#include <deque>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

namespace subfeed::sim {

class ExecutionLog {
public:
  ExecutionLog() = default; // logs nothing
  explicit ExecutionLog(const std::filesystem::path& path) : out_(path, std::ios::app) {}

  // A line accepted; `queued_move`: it put a block (move or dwell) in the planner queue.
  void accepted(std::string line, bool queued_move);
  // The planner finished `blocks` more blocks.
  void finished(std::size_t blocks);
  // The queue was dropped (reset, alarm): what waited on it never runs.
  void dropped();

private:
  void flush();

  std::ofstream out_;
  std::deque<std::pair<std::size_t, std::string>> waiting_; // block count each waits for
  std::size_t queued_ = 0, done_ = 0;
};

} // namespace subfeed::sim
