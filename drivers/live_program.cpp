#include "drivers/live_program.hpp"

namespace subfeed::drivers {

namespace {

Error read_twice(const std::string& name) {
  return Error{
      ErrorCode::usage, "a program that is still being posted cannot be read twice", {name, 0, {}}};
}

} // namespace

Expected<void> LiveGcode::rewind() {
  if (line_ > 0) {
    return std::unexpected(read_twice(name_));
  }
  return {};
}

Expected<SourceLine> LiveGcode::prepare(Expected<std::string> item) {
  if (!item) {
    return std::unexpected(item.error());
  }
  ++line_;
  SUBFEED_TRY_ASSIGN(auto prepared,
                     prepare_line(*item, rules_, {name_, static_cast<int>(line_), {}}));
  return SourceLine{line_, std::move(prepared)};
}

bool LiveGcode::ready(std::chrono::milliseconds wait) {
  while (!ready_) {
    if (!queue_->ready(wait)) {
      return false;
    }
    auto item = queue_->pop();
    if (!item) {
      return true; // closed and drained: next() ends at once
    }
    auto line = prepare(std::move(*item));
    if (!line || !line->line.text.empty()) {
      ready_ = std::move(line);
    }
    wait = std::chrono::milliseconds(0); // one wait per call, however many blank lines
  }
  return true;
}

Expected<std::optional<SourceLine>> LiveGcode::next() {
  if (ready_) {
    auto line = std::move(*ready_);
    ready_.reset();
    if (!line) {
      return std::unexpected(line.error());
    }
    return std::move(*line);
  }
  while (auto item = queue_->pop()) {
    SUBFEED_TRY_ASSIGN(auto line, prepare(std::move(*item)));
    if (!line.line.text.empty()) {
      return line;
    }
  }
  return std::optional<SourceLine>();
}

Expected<std::optional<std::string>> LiveBlocks::take() {
  if (peeked_) {
    auto text = std::move(*peeked_);
    peeked_.reset();
    return text;
  }
  auto item = queue_->pop();
  if (!item) {
    return std::optional<std::string>();
  }
  if (!*item) {
    return std::unexpected(item->error());
  }
  ++line_;
  return std::move(**item);
}

Expected<FanucScan> LiveBlocks::scan() {
  FanucScan scan;
  if (line_ == 0) {
    SUBFEED_TRY_ASSIGN(peeked_, take());
  }
  scan.framed = peeked_ && *peeked_ == "%";
  return scan;
}

Expected<void> LiveBlocks::rewind() {
  if (line_ > 1 || (line_ == 1 && !peeked_)) {
    return std::unexpected(read_twice(name_));
  }
  return {};
}

bool LiveBlocks::ready(std::chrono::milliseconds wait) {
  return peeked_ || queue_->ready(wait);
}

Expected<bool> LiveBlocks::next(FanucBlock& block) {
  while (true) {
    const long line = peeked_ ? line_ : line_ + 1;
    SUBFEED_TRY_ASSIGN(auto text, take());
    if (!text) {
      return false;
    }
    while (!text->empty() && (text->back() == '\r' || text->back() == ' ')) {
      text->pop_back();
    }
    if (text->empty()) {
      continue;
    }
    SUBFEED_TRY(check_tape_block(*text, {name_, static_cast<int>(line), {}}));
    block.line = line;
    block.text = std::move(*text);
    return true;
  }
}

} // namespace subfeed::drivers
