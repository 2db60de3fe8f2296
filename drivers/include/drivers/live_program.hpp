#pragma once
// A program that is still being written while it is sent: lines arrive through a bounded
// queue from the post, so the controller can start before planning has finished and memory
// stays bounded however long the job. The producer pushes each line as it will appear in
// the program file (so line numbers match the file), an Error if it fails, and closes the
// queue at the end. A live program is read once: it cannot be scanned ahead or rewound
// after its first line, so the whole-file checks of a file source happen line by line.

#include "base/bounded_queue.hpp"
#include "drivers/block_source.hpp"
#include "drivers/line_source.hpp"

#include <optional>
#include <string>

namespace subfeed::drivers {

using ProgramQueue = BoundedQueue<Expected<std::string>>;

// For the GRBL streamer.
class LiveGcode final : public LineSource {
public:
  LiveGcode(std::string name, ProgramQueue& queue) : name_(std::move(name)), queue_(&queue) {}

  [[nodiscard]] const std::string& name() const override { return name_; }
  void set_rules(const LineRules& rules) override { rules_ = rules; }
  [[nodiscard]] Expected<ScanSummary> scan() override { return ScanSummary{}; }
  [[nodiscard]] Expected<void> rewind() override;
  [[nodiscard]] Expected<std::optional<SourceLine>> next() override;
  // Blank and comment-only lines are taken here as they come, so that next() after a true
  // answer never waits for the producer.
  [[nodiscard]] bool ready(std::chrono::milliseconds wait) override;

private:
  // The next item prepared: a line to send, a blank one (text empty), or the producer's error.
  [[nodiscard]] Expected<SourceLine> prepare(Expected<std::string> item);

  std::string name_;
  ProgramQueue* queue_;
  LineRules rules_;
  long line_ = 0;
  std::optional<Expected<SourceLine>> ready_; // taken by ready(), handed on by next()
};

// For the Fanuc drip feed. scan() waits for the first line to learn whether the program
// brings its own '%' framing.
class LiveBlocks final : public BlockSource {
public:
  LiveBlocks(std::string name, ProgramQueue& queue) : name_(std::move(name)), queue_(&queue) {}

  [[nodiscard]] const std::string& name() const override { return name_; }
  [[nodiscard]] Expected<FanucScan> scan() override;
  [[nodiscard]] Expected<void> rewind() override;
  [[nodiscard]] Expected<bool> next(FanucBlock& block) override;
  [[nodiscard]] bool ready(std::chrono::milliseconds wait) override;

private:
  [[nodiscard]] Expected<std::optional<std::string>> take();

  std::string name_;
  ProgramQueue* queue_;
  std::optional<std::string> peeked_;
  long line_ = 0;
};

} // namespace subfeed::drivers
