#include "drivers/grbl_streamer.hpp"

#include "drivers/line_ranges.hpp"

#include <algorithm>
#include <deque>
#include <poll.h>

namespace subfeed::drivers {

namespace {

using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;
namespace rt = grbl_realtime;

constexpr int fallback_rx_buffer = 128;
constexpr int grbl_line_limit = 79;
constexpr int grblhal_line_limit = 256;
constexpr auto write_timeout = 2000ms;
constexpr auto lost_ack_after = 1000ms;
constexpr auto reset_banner_wait = 3000ms;

struct InFlight {
  long file_line = 0; // 0 for the sender's own commands ($I, $C, latch clearing)
  int bytes = 0;      // counted in the RX buffer, '\n' included
  bool alone = false; // nothing may follow it until it is answered
  bool clears_latch = false;
  Clock::time_point sent_at{};
};

class GrblStreamer {
public:
  GrblStreamer(Transport& link, LineSource& source, const GrblStreamOptions& options,
               ControlInbox* inbox, StreamObserver& observer)
      : link_(link), source_(source), options_(options), inbox_(inbox), observer_(observer) {}

  Expected<StreamSummary> run() {
    start_ = last_byte_at_ = last_ack_at_ = Clock::now();
    SUBFEED_TRY(handshake());
    source_.set_rules({info_.line_limit, options_.keep_comments});
    SUBFEED_TRY_ASSIGN(const ScanSummary scan, source_.scan());
    lines_total_ = scan.lines_to_send;
    observer_.connected(info_);
    if (options_.check_first) {
      SUBFEED_TRY(check_pass());
    }
    observer_.phase("stream");
    start_ = Clock::now();
    SUBFEED_TRY(stream_pass());
    observer_.phase("finishing");
    SUBFEED_TRY(wait_until_idle());
    return summary();
  }

private:
  // ---- the wire ---------------------------------------------------------------------------

  Expected<void> write_bytes(std::string_view bytes) {
    if (auto ok = write_all(link_, bytes, write_timeout); !ok) {
      return link_lost(ok.error());
    }
    return {};
  }

  Expected<void> realtime(unsigned char byte) {
    const char c = static_cast<char>(byte);
    return write_bytes(std::string_view(&c, 1));
  }

  Expected<void> send_bytes_counted(const std::string& text, InFlight entry) {
    std::string wire = text;
    wire += '\n';
    entry.bytes = static_cast<int>(wire.size());
    entry.sent_at = Clock::now();
    in_flight_.push_back(entry);
    rx_used_ += entry.bytes;
    if (entry.file_line > 0) {
      bytes_sent_ += entry.bytes; // the program's bytes; the sender's own commands are not
      observer_.line_sent(entry.file_line, entry.bytes);
    }
    return write_bytes(wire);
  }

  // Waits until the link or the inbox has something, at most `timeout`; reads and handles
  // every complete line that arrived.
  Expected<void> pump(std::chrono::milliseconds timeout) {
    pollfd fds[2] = {{link_.poll_fd(), POLLIN, 0}, {inbox_ ? inbox_->fd() : -1, POLLIN, 0}};
    ::poll(fds, inbox_ ? 2 : 1, static_cast<int>(std::max(timeout, 0ms).count()));
    if (fds[0].revents == 0) {
      return {};
    }
    char buffer[512];
    auto n = link_.read(buffer, 0ms);
    if (!n) {
      return link_lost(n.error());
    }
    if (*n > 0) {
      last_byte_at_ = Clock::now();
    }
    for (std::size_t i = 0; i < *n; ++i) {
      if (buffer[i] == '\n') {
        if (!partial_.empty() && partial_.back() == '\r') {
          partial_.pop_back();
        }
        on_line(partial_);
        partial_.clear();
      } else if (partial_.size() < 4096) { // line noise without an end cannot grow forever
        partial_ += buffer[i];
      }
    }
    return {};
  }

  // ---- replies ----------------------------------------------------------------------------

  void on_line(std::string_view line) {
    const Reply reply = classify_reply(line);
    switch (reply.kind) {
    case ReplyKind::ok:
    case ReplyKind::error:
      on_answer(reply);
      break;
    case ReplyKind::alarm:
      on_alarm(reply.code);
      break;
    case ReplyKind::banner:
      on_banner(reply);
      break;
    case ReplyKind::status:
      on_status(line);
      break;
    case ReplyKind::feedback:
      on_feedback(line);
      break;
    case ReplyKind::setting:
    case ReplyKind::startup_echo:
      observer_.message(line);
      break;
    case ReplyKind::empty:
      break;
    case ReplyKind::unknown:
      ++unknown_;
      break;
    }
  }

  void on_answer(const Reply& reply) {
    const int code = reply.kind == ReplyKind::ok ? 0 : reply.code;
    if (in_flight_.empty()) {
      if (lost_in_reset_.size() > answers_after_reset_.size()) {
        // The controller reset itself: what it still answers are the last lines sent, which
        // reached it after its restart. Which ones is known once it has been stopped.
        answers_after_reset_.push_back(code);
        return;
      }
      ++unknown_; // an answer to nothing (e.g. a CRLF's second ok): never retires a line
      return;
    }
    const InFlight line = in_flight_.front();
    in_flight_.pop_front();
    rx_used_ -= line.bytes;
    last_ack_at_ = Clock::now();
    if (line.clears_latch) {
      latch_code_ = 0;
    }
    if (line.file_line == 0) {
      command_reply_ = code;
      return;
    }
    retire(line.file_line, code);
  }

  void retire(long file_line, int code) {
    ++lines_acked_;
    last_acked_line_ = file_line;
    observer_.line_answered(file_line, code);
    if (code != 0) {
      if (fault_) {
        not_run_.push_back(file_line); // refused after the fault (grblHAL's latch, error:9)
      } else {
        on_line_error(file_line, code);
      }
    }
    report_progress();
  }

  void on_line_error(long file_line, int code) {
    if (!options_.continue_on_error && !checking_) {
      // Stop motion first: the lines behind this one are already in the controller.
      (void)realtime(rt::feed_hold);
      fail_with(ErrorCode::machine_fault,
                "controller error:" + std::to_string(code) + " (" +
                    std::string(error_meaning(code)) + ")",
                file_line);
      return;
    }
    ++errors_;
    if (first_error_line_ == 0) {
      first_error_line_ = file_line;
      first_error_code_ = code;
    }
    const bool latched = info_.grblhal && latch_code_ == code;
    observer_.line_error({source_.name(), file_line, code, latched});
    if (info_.grblhal && latch_code_ == 0) {
      latch_code_ = code; // every following line gets the same error until cleared
      clear_latch_ = true;
    }
  }

  void on_alarm(int code) {
    observer_.link_event("alarm", "ALARM:" + std::to_string(code));
    fail_with(ErrorCode::machine_fault,
              "controller ALARM:" + std::to_string(code) + " (" + std::string(alarm_meaning(code)) +
                  "); streaming stopped",
              last_acked_line_);
    motion_stopped_ = true; // the controller stopped itself
  }

  void on_banner(const Reply& reply) {
    info_.grblhal = reply.grblhal;
    if (connecting_ || expecting_reset_) {
      info_.banner = std::string(reply.text);
      banner_seen_ = true;
      return;
    }
    observer_.link_event("reset", reply.text);
    fail_with(ErrorCode::machine_fault, "the controller reset itself (welcome message mid-job)",
              last_acked_line_);
    // Its buffers are empty now, but lines still on their way will run: it is held and
    // reset as after an error, and what it answers meanwhile is matched to the newest lines.
    settle_reset();
    lost_in_reset_.assign(in_flight_.begin(), in_flight_.end());
    in_flight_.clear();
    rx_used_ = 0;
  }

  // Matches the answers given since the controller reset itself to the newest of the lines
  // it held then; the older ones were lost in the reset.
  void settle_reset() {
    const std::size_t answered = std::min(answers_after_reset_.size(), lost_in_reset_.size());
    const std::size_t lost = lost_in_reset_.size() - answered;
    for (std::size_t i = 0; i < lost_in_reset_.size(); ++i) {
      const long file_line = lost_in_reset_[i].file_line;
      if (file_line == 0) {
        continue;
      }
      if (i < lost) {
        not_run_.push_back(file_line);
      } else {
        retire(file_line, answers_after_reset_[i - lost]);
      }
    }
    lost_in_reset_.clear();
    answers_after_reset_.clear();
  }

  void on_status(std::string_view line) {
    auto status = parse_status(line);
    if (!status) {
      ++unknown_;
      return;
    }
    status_ = std::move(*status);
    status_at_ = Clock::now();
    report_progress();
  }

  void on_feedback(std::string_view line) {
    if (line.starts_with("[VER:")) {
      std::string_view version = line.substr(5, line.size() - 6);
      if (version.ends_with(':')) { // [VER:1.1h.20190825:] has an empty build-name field
        version.remove_suffix(1);
      }
      info_.version = std::string(version);
    } else if (line.starts_with("[OPT:")) {
      const BuildOptions build = parse_build_options(line);
      if (build.rx_buffer) {
        info_.rx_buffer = *build.rx_buffer;
        info_.rx_buffer_reported = true;
      }
      info_.planner_blocks = build.planner_blocks;
    } else if (line == "[FIRMWARE:grblHAL]" || line.starts_with("[NEWOPT:")) {
      info_.grblhal = true; // grblHAL on native USB or Ethernet never sends a banner
    }
    observer_.message(line);
  }

  // ---- faults -----------------------------------------------------------------------------

  void fail_with(ErrorCode code, std::string message, long file_line) {
    if (!fault_) {
      fault_ = Error{code, std::move(message), {source_.name(), static_cast<int>(file_line), {}}};
    }
  }

  std::unexpected<Error> link_lost(const Error& cause) {
    motion_stopped_ = true; // nothing more can be said to the controller
    return fail(ErrorCode::machine_fault,
                cause.message + " (" + link_.name() + ")" + acked_note() +
                    lines_note(unanswered_lines(), "sent and not acknowledged"),
                {source_.name(), static_cast<int>(last_acked_line_), {}});
  }

  [[nodiscard]] std::string acked_note() const {
    return last_acked_line_ > 0 ? "; last line acknowledged: " + std::to_string(last_acked_line_)
                                : "; no line was acknowledged";
  }

  [[nodiscard]] std::vector<long> unanswered_lines() const {
    std::vector<long> lines;
    for (const auto& f : in_flight_) {
      if (f.file_line > 0) {
        lines.push_back(f.file_line);
      }
    }
    return lines;
  }

  // "; 3 line(s) <what> (lines 41-43)", or nothing for no lines.
  static std::string lines_note(const std::vector<long>& lines, std::string_view what) {
    if (lines.empty()) {
      return "";
    }
    return "; " + std::to_string(lines.size()) + " line(s) " + std::string(what) + " (" +
           describe_lines(lines) + ")";
  }

  // What became of the lines sent, once the controller has been stopped: acknowledged, or
  // refused and dropped (not run), or, when it could not be stopped, still waiting in it.
  [[nodiscard]] std::string outcome_note(bool stopped) {
    settle_reset();
    std::vector<long> not_run = not_run_;
    std::vector<long> waiting = unanswered_lines();
    if (stopped) { // an alarmed controller runs nothing more; a reset emptied it
      not_run.insert(not_run.end(), waiting.begin(), waiting.end());
      waiting.clear();
    }
    return acked_note() + lines_note(not_run, "sent but not run") +
           lines_note(waiting, "sent and not answered, still in the controller");
  }

  // Brings the machine to a safe stop after a fault or a stop command: feed hold, wait for
  // Hold:0, then a soft reset that clears the controller's buffers without ALARM:3.
  Expected<void> stop_machine() {
    if (motion_stopped_) {
      return {};
    }
    motion_stopped_ = true;
    observer_.link_event("hold", "stopping the machine");
    if (auto held = realtime(rt::feed_hold); !held) {
      return held;
    }
    const auto deadline = Clock::now() + options_.hold_timeout;
    status_.reset();
    while (Clock::now() < deadline) {
      SUBFEED_TRY(realtime(rt::status));
      const auto next = Clock::now() + 50ms;
      while (Clock::now() < next) {
        SUBFEED_TRY(
            pump(std::chrono::duration_cast<std::chrono::milliseconds>(next - Clock::now())));
      }
      if (status_ && (status_->state == "Idle" || status_->state == "Alarm" ||
                      (status_->state == "Hold" && status_->substate == 0))) {
        expect_reset();
        observer_.link_event("reset", "soft reset after Hold:0");
        SUBFEED_TRY(realtime(rt::soft_reset));
        return wait_for_banner(reset_banner_wait);
      }
    }
    return fail(ErrorCode::machine_fault,
                "the machine did not report Hold:0 within " +
                    std::to_string(options_.hold_timeout.count()) +
                    " ms; it was left in feed hold and not reset",
                {link_.name(), 0, {}});
  }

  // Before the command that resets the controller: its banner may come in the same read as
  // the command's own answer.
  void expect_reset() {
    expecting_reset_ = true;
    banner_seen_ = false;
  }

  Expected<void> wait_for_banner(std::chrono::milliseconds timeout) {
    const auto deadline = Clock::now() + timeout;
    while (!banner_seen_ && Clock::now() < deadline) {
      SUBFEED_TRY(pump(20ms));
    }
    expecting_reset_ = false;
    const auto dropped = unanswered_lines(); // a reset empties the controller's buffers
    not_run_.insert(not_run_.end(), dropped.begin(), dropped.end());
    in_flight_.clear();
    rx_used_ = 0;
    return {};
  }

  // The program could not give its next line (a live job's planner or motion gate refused
  // the path): what was sent is all that may run; the machine is held and reset.
  Expected<void> source_failed(const Error& error) {
    if (!fault_) {
      fault_ = error;
    }
    return check_fault();
  }

  // Turns a recorded fault into the stream's result, after stopping the machine; the report
  // of what ran is made only then, when every answer the controller still gave is in.
  Expected<void> check_fault() {
    if (!fault_) {
      return {};
    }
    Error error = *fault_;
    const bool stopped_itself = motion_stopped_;
    const auto stopped = stop_machine();
    if (stopped_itself) {
      settle();
    }
    error.message += outcome_note(stopped.has_value());
    if (!stopped) {
      error.message += "; " + stopped.error().message;
    }
    return std::unexpected(error);
  }

  // Reads what an alarmed controller still says, until it has been quiet a while.
  void settle() {
    const auto deadline = Clock::now() + 1000ms;
    while (Clock::now() < deadline && Clock::now() - last_byte_at_ < 150ms) {
      if (!pump(20ms)) {
        return;
      }
    }
  }

  Expected<void> handle_inbox() {
    if (inbox_ == nullptr) {
      return {};
    }
    for (const ControlCommand& command : inbox_->take()) {
      if (command.kind == ControlCommand::Kind::stop) {
        fail_with(ErrorCode::stopped, "stopped by the user", last_acked_line_);
      } else {
        SUBFEED_TRY(realtime(command.byte));
      }
    }
    return {};
  }

  // Status polls always expect an answer, so silence means a lost controller at any time,
  // also while waiting for the last moves to finish.
  Expected<void> check_silence() {
    const auto now = Clock::now();
    if (now - last_byte_at_ > options_.silence_timeout) {
      fail_with(ErrorCode::machine_fault,
                "no answer from the controller for " +
                    std::to_string(options_.silence_timeout.count()) + " ms",
                last_acked_line_);
    } else if (!in_flight_.empty() && status_ &&
               (status_->state == "Idle" || status_->state == "Check") &&
               status_at_ > std::max(last_ack_at_, in_flight_.front().sent_at) + lost_ack_after) {
      // Answers carry no line number: after a lost one every later answer retired the line
      // before its own, so which line lost its answer cannot be told.
      fail_with(
          ErrorCode::machine_fault,
          "acknowledgement lost: the controller is idle but " + std::to_string(in_flight_.size()) +
              " line(s) are unanswered; the last line sent was " + std::to_string(last_sent_line_),
          last_sent_line_);
    }
    return {};
  }

  // ---- status polling ---------------------------------------------------------------------

  Expected<void> poll_status_when_due() {
    const auto now = Clock::now();
    if (now >= next_poll_at_) {
      next_poll_at_ = now + std::chrono::duration_cast<Clock::duration>(
                                std::chrono::duration<double>(1.0 / options_.status_hz));
      return realtime(rt::status);
    }
    return {};
  }

  [[nodiscard]] std::chrono::milliseconds until_next_poll() const {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(next_poll_at_ - Clock::now());
    return std::clamp(left, 0ms, 50ms);
  }

  // One round of the loops below: faults, commands, polls, and waiting for input.
  Expected<void> turn() {
    SUBFEED_TRY(check_fault());
    SUBFEED_TRY(handle_inbox());
    SUBFEED_TRY(check_fault());
    SUBFEED_TRY(check_silence());
    SUBFEED_TRY(poll_status_when_due());
    return pump(until_next_poll());
  }

  // ---- phases -----------------------------------------------------------------------------

  Expected<void> handshake() {
    connecting_ = true;
    const auto deadline = Clock::now() + options_.connect_timeout;
    auto probe_at = Clock::now() + 300ms; // an Arduino GRBL speaks first, after its boot
    while (!banner_seen_ && !status_ && Clock::now() < deadline) {
      SUBFEED_TRY(handle_inbox());
      if (fault_) {
        return std::unexpected(*fault_); // stopped before anything was sent: nothing to hold
      }
      if (Clock::now() >= probe_at) {
        SUBFEED_TRY(realtime(rt::status));
        probe_at = Clock::now() + 500ms;
      }
      SUBFEED_TRY(pump(20ms));
    }
    if (!banner_seen_ && !status_) {
      return fail(ErrorCode::machine_fault,
                  "no answer from a GRBL controller within " +
                      std::to_string(options_.connect_timeout.count()) +
                      " ms (is it powered, and are the port and baud rate right?)",
                  {link_.name(), 0, {}});
    }
    SUBFEED_TRY(require_idle());
    SUBFEED_TRY(command("$I"));
    connecting_ = false;
    if (options_.rx_buffer) {
      info_.rx_buffer = *options_.rx_buffer;
      info_.rx_buffer_reported = false;
    } else if (!info_.rx_buffer_reported) {
      info_.rx_buffer = fallback_rx_buffer;
    }
    info_.line_limit =
        options_.line_limit.value_or(info_.grblhal ? grblhal_line_limit : grbl_line_limit);
    return {};
  }

  Expected<void> fresh_status(std::chrono::milliseconds timeout) {
    const auto asked = Clock::now();
    SUBFEED_TRY(realtime(rt::status));
    const auto deadline = asked + timeout;
    while (!(status_ && status_at_ >= asked) && Clock::now() < deadline) {
      SUBFEED_TRY(pump(20ms));
    }
    if (!(status_ && status_at_ >= asked)) {
      return fail(ErrorCode::machine_fault, "the controller does not answer status queries",
                  {link_.name(), 0, {}});
    }
    return {};
  }

  Expected<void> require_idle() {
    SUBFEED_TRY(fresh_status(2000ms));
    if (status_->state == "Alarm") {
      return fail(ErrorCode::machine_fault,
                  "the controller is in ALARM state: home it ($H) or unlock it ($X) first",
                  {link_.name(), 0, {}});
    }
    if (status_->state != "Idle") {
      return fail(ErrorCode::machine_fault,
                  "the controller is busy (state " + status_->state + "); start when it is Idle",
                  {link_.name(), 0, {}});
    }
    return {};
  }

  // Sends one of the sender's own commands alone and waits for its answer.
  Expected<void> command(const std::string& text) {
    command_reply_.reset();
    SUBFEED_TRY(send_bytes_counted(text, {0, 0, true, false}));
    const auto deadline = Clock::now() + options_.silence_timeout;
    while (!command_reply_ && Clock::now() < deadline) {
      SUBFEED_TRY(check_fault());
      SUBFEED_TRY(pump(20ms));
    }
    if (!command_reply_) {
      return fail(ErrorCode::machine_fault, "no answer to " + text, {link_.name(), 0, {}});
    }
    if (*command_reply_ != 0 && text != "$I") { // a controller without $I still streams
      return fail(ErrorCode::machine_fault,
                  text + " answered error:" + std::to_string(*command_reply_) + " (" +
                      std::string(error_meaning(*command_reply_)) + ")",
                  {link_.name(), 0, {}});
    }
    return {};
  }

  Expected<void> check_pass() {
    observer_.phase("check");
    SUBFEED_TRY(command("$C"));
    checking_ = true;
    SUBFEED_TRY(stream_pass());
    checking_ = false;
    expect_reset(); // leaving check mode resets the controller
    SUBFEED_TRY(command("$C"));
    SUBFEED_TRY(wait_for_banner(reset_banner_wait));
    if (errors_ > 0) {
      return fail(ErrorCode::bad_input,
                  "check mode found " + std::to_string(errors_) +
                      " line(s) in error, the first error:" + std::to_string(first_error_code_) +
                      " (" + std::string(error_meaning(first_error_code_)) + "); nothing was run",
                  {source_.name(), static_cast<int>(first_error_line_), {}});
    }
    SUBFEED_TRY(require_idle());
    lines_acked_ = lines_sent_ = 0;
    bytes_sent_ = 0;
    last_acked_line_ = 0;
    return {};
  }

  [[nodiscard]] bool alone(const SourceLine& line) const {
    return line.line.send_and_wait || options_.send_and_wait;
  }

  // Whether `line` may go now; may ask for a status report it needs first.
  Expected<bool> may_send(const SourceLine& line) {
    const int bytes = static_cast<int>(line.line.text.size()) + 1;
    if (bytes > info_.rx_buffer) {
      return fail(ErrorCode::bad_input,
                  "line needs " + std::to_string(bytes) + " bytes; the controller's buffer holds " +
                      std::to_string(info_.rx_buffer),
                  {source_.name(), static_cast<int>(line.number), {}});
    }
    if (!in_flight_.empty() && in_flight_.back().alone) {
      return false;
    }
    if (alone(line)) {
      if (!in_flight_.empty()) {
        return false;
      }
      // System commands need an idle controller (else error:8): wait for the planner to empty.
      if (line.line.text.front() == '$' && !checking_) {
        const bool idle = status_ && status_at_ > last_ack_at_ && status_->state == "Idle";
        if (!idle && Clock::now() + 50ms < next_poll_at_) {
          next_poll_at_ = Clock::now() + 50ms;
        }
        return idle;
      }
      return true;
    }
    return rx_used_ + bytes <= info_.rx_buffer;
  }

  Expected<void> stream_pass() {
    SUBFEED_TRY(source_.rewind());
    last_byte_at_ = Clock::now(); // scanning a long file is not the controller's silence
    std::optional<SourceLine> next;
    bool end_of_file = false;
    while (true) {
      SUBFEED_TRY(turn_and_clear_latch());
      while (!end_of_file && !fault_) { // not one line more once a fault has been read
        if (!next) {
          if (!source_.ready(until_next_poll())) {
            break; // the program's writer is still at work: serve the controller meanwhile
          }
          auto read = source_.next();
          if (!read) {
            return source_failed(read.error());
          }
          next = std::move(*read);
          end_of_file = !next;
          if (end_of_file) {
            break;
          }
        }
        SUBFEED_TRY_ASSIGN(const bool go, may_send(*next));
        if (!go) {
          break;
        }
        SUBFEED_TRY(send_bytes_counted(next->line.text, {next->number, 0, alone(*next), false}));
        ++lines_sent_;
        last_sent_line_ = next->number;
        next.reset();
      }
      if (end_of_file && in_flight_.empty()) {
        return check_fault();
      }
    }
  }

  Expected<void> turn_and_clear_latch() {
    if (clear_latch_ && !fault_ && rx_used_ + 1 <= info_.rx_buffer) {
      clear_latch_ = false; // grblHAL: an empty line ends the error latch
      SUBFEED_TRY(send_bytes_counted("", {0, 0, false, true}));
    }
    return turn();
  }

  Expected<void> wait_until_idle() {
    while (true) {
      SUBFEED_TRY(turn());
      if (status_ && status_at_ > last_ack_at_ && status_->state == "Idle") {
        return {};
      }
    }
  }

  void report_progress() {
    if (connecting_) {
      return; // nothing to show before the file has been scanned
    }
    StreamProgress p;
    p.lines_total = lines_total_;
    p.lines_sent = lines_sent_;
    p.lines_acked = lines_acked_;
    p.bytes_sent = bytes_sent_;
    p.rx_in_flight = rx_used_;
    p.elapsed_s = std::chrono::duration<double>(Clock::now() - start_).count();
    p.checking = checking_;
    p.status = status_;
    observer_.progress(p);
  }

  StreamSummary summary() const {
    StreamSummary s;
    s.controller = info_;
    s.lines = lines_acked_;
    s.bytes = bytes_sent_;
    s.errors = errors_;
    s.seconds = std::chrono::duration<double>(Clock::now() - start_).count();
    s.unknown_replies = unknown_;
    return s;
  }

  Transport& link_;
  LineSource& source_;
  const GrblStreamOptions& options_;
  ControlInbox* inbox_;
  StreamObserver& observer_;

  ControllerInfo info_;
  std::deque<InFlight> in_flight_;
  std::vector<long> not_run_;            // refused after a fault, or dropped by a reset
  std::vector<InFlight> lost_in_reset_;  // in flight when the controller reset itself
  std::vector<int> answers_after_reset_; // its answers since, 0 for ok
  int rx_used_ = 0;
  std::string partial_;
  std::optional<StatusReport> status_;
  std::optional<Error> fault_;
  std::optional<int> command_reply_;
  Clock::time_point start_{}, last_byte_at_{}, last_ack_at_{}, status_at_{}, next_poll_at_{};
  long lines_total_ = 0, lines_sent_ = 0, lines_acked_ = 0, bytes_sent_ = 0;
  long errors_ = 0, unknown_ = 0, last_acked_line_ = 0, last_sent_line_ = 0, first_error_line_ = 0;
  int first_error_code_ = 0;
  int latch_code_ = 0;
  bool clear_latch_ = false;
  bool connecting_ = false;
  bool banner_seen_ = false;
  bool expecting_reset_ = false;
  bool checking_ = false;
  bool motion_stopped_ = false;
};

} // namespace

Expected<StreamSummary> stream_grbl(Transport& link, LineSource& source,
                                    const GrblStreamOptions& options, ControlInbox* inbox,
                                    StreamObserver& observer) {
  GrblStreamer streamer(link, source, options, inbox, observer);
  return streamer.run();
}

} // namespace subfeed::drivers
