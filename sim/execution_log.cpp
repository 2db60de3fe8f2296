#include "sim/execution_log.hpp"

namespace subfeed::sim {

void ExecutionLog::accepted(std::string line, bool queued_move) {
  if (!out_.is_open()) {
    return;
  }
  queued_ += queued_move ? 1 : 0;
  waiting_.emplace_back(queued_, std::move(line));
  flush();
}

void ExecutionLog::finished(std::size_t blocks) {
  done_ += blocks;
  flush();
}

void ExecutionLog::dropped() {
  waiting_.clear();
  queued_ = done_;
}

void ExecutionLog::flush() {
  if (waiting_.empty() || waiting_.front().first > done_) {
    return;
  }
  while (!waiting_.empty() && waiting_.front().first <= done_) {
    out_ << waiting_.front().second << '\n';
    waiting_.pop_front();
  }
  out_.flush();
}

} // namespace subfeed::sim
