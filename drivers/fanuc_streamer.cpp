#include "drivers/fanuc_streamer.hpp"

#include "gcode/modal_state.hpp"

#include <cstdio>
#include <poll.h>

namespace subfeed::drivers {

namespace {

using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

constexpr char dc1 = 0x11; // XON: the control asks for (more of) the tape
constexpr char dc3 = 0x13; // XOFF: the control's buffer is nearly full
constexpr auto write_timeout = 2000ms;
// Below this a character cannot be timed one by one; send several per write.
constexpr auto finest_pacing = std::chrono::microseconds(500);

class FanucStreamer {
public:
  FanucStreamer(Transport& link, BlockSource& program, const FanucStreamOptions& options,
                ControlInbox* inbox, StreamObserver& observer)
      : link_(link), program_(program), options_(options), inbox_(inbox), observer_(observer),
        eob_(options.eia_cr ? '\r' : '\n') {
    const double seconds =
        static_cast<double>(bits_per_character(options.serial)) / options.serial.baud;
    character_time_ =
        std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
    chunk_ = std::max<long>(1, finest_pacing / std::max(character_time_, Clock::duration(1)));
  }

  Expected<StreamSummary> run() {
    SUBFEED_TRY(wait_for_program());
    SUBFEED_TRY_ASSIGN(const FanucScan scan, program_.scan());
    for (const auto& b : options_.restart_blocks) { // before anything is on the tape
      SUBFEED_TRY(check_tape_block(b, {program_.name(), 0, "resume"}));
    }
    total_ = scan.blocks + (scan.framed ? 0 : 3);
    if (options_.wait_for_request) {
      SUBFEED_TRY(wait_for_request());
    }
    start_ = next_at_ = Clock::now();
    observer_.phase("stream");
    SUBFEED_TRY(send_raw(std::string(static_cast<std::size_t>(options_.nul_leader), '\0')));
    if (!scan.framed) {
      char number[16];
      std::snprintf(number, sizeof number, "O%04d", options_.program_number);
      SUBFEED_TRY(send_block("%", 0));
      SUBFEED_TRY(send_block(number, 0));
    }
    SUBFEED_TRY(send_program());
    if (!scan.framed) {
      SUBFEED_TRY(send_block("%", 0));
    }
    SUBFEED_TRY(send_raw(std::string(static_cast<std::size_t>(options_.nul_trailer), '\0')));
    StreamSummary summary;
    summary.lines = blocks_sent_;
    summary.bytes = bytes_sent_;
    // Until the last character has crossed the wire, not just left the program.
    summary.seconds =
        std::chrono::duration<double>(std::max(Clock::now(), next_at_) - start_).count();
    return summary;
  }

private:
  Expected<void> send_program() {
    gcode::ModalState modal;
    bool restored = !options_.from_line;
    FanucBlock block;
    while (true) {
      SUBFEED_TRY(wait_for_program());
      SUBFEED_TRY_ASSIGN(const bool more, program_.next(block));
      if (!more) {
        if (!restored) {
          return fail(ErrorCode::bad_input,
                      "the program ends before line " + std::to_string(*options_.from_line),
                      {program_.name(), 0, "--from"});
        }
        return {};
      }
      SUBFEED_TRY(send_or_apply(block, modal, restored));
    }
  }

  // Blocks before --from only build up the modal state; '%' and the O line still go.
  Expected<void> send_or_apply(const FanucBlock& block, gcode::ModalState& modal, bool& restored) {
    const char first = block.text.front();
    const bool framing = block.text == "%" || first == 'O' || first == ':';
    if (!restored && block.line >= *options_.from_line && !framing) {
      SUBFEED_TRY_ASSIGN(
          const auto blocks,
          modal.restore_blocks({program_.name(), static_cast<int>(block.line), "--from"}));
      for (const auto& b : blocks) {
        SUBFEED_TRY(send_block(b, 0));
      }
      for (const auto& b : options_.restart_blocks) {
        SUBFEED_TRY(send_block(b, 0));
      }
      restored = true;
    }
    if (restored || framing) {
      return send_block(block.text, block.line);
    }
    return modal.apply(block.text, {program_.name(), static_cast<int>(block.line), {}});
  }

  Expected<void> send_block(const std::string& text, long line) {
    SUBFEED_TRY(send_raw(text + eob_));
    ++blocks_sent_;
    observer_.line_sent(line, static_cast<long>(text.size()) + 1);
    last_line_ = line != 0 ? line : last_line_;
    report();
    return {};
  }

  // Paces `bytes` at the character rate, honouring DC3/DC1 between characters.
  Expected<void> send_raw(const std::string& bytes) {
    std::size_t at = 0;
    while (at < bytes.size()) {
      SUBFEED_TRY(service(0ns));
      if (paused_) {
        SUBFEED_TRY(wait_while_paused());
        continue;
      }
      const auto now = Clock::now();
      if (now < next_at_) {
        SUBFEED_TRY(service(next_at_ - now));
        continue;
      }
      const std::size_t n =
          std::min<std::size_t>(static_cast<std::size_t>(chunk_), bytes.size() - at);
      SUBFEED_TRY(write_now(std::string_view(bytes).substr(at, n)));
      at += n;
      bytes_sent_ += static_cast<long>(n);
      // A late wake-up is made up for by half a character at most: the average rate stays
      // close to the line's, and no two characters leave closer than half a character
      // apart, so a DC3 is seen before a second one follows.
      next_at_ =
          std::max(next_at_, now - character_time_ / 2) + character_time_ * static_cast<long>(n);
    }
    return {};
  }

  Expected<void> write_now(std::string_view bytes) {
    auto written = link_.write(bytes, write_timeout);
    if (!written) {
      return lost(written.error().message);
    }
    if (*written < bytes.size()) {
      return lost("the port took nothing for " + std::to_string(write_timeout.count()) +
                  " ms (hardware handshake: CTS held low?)");
    }
    return {};
  }

  Expected<void> wait_while_paused() {
    if (Clock::now() - paused_since_ > options_.xoff_timeout) {
      return fail(ErrorCode::machine_fault,
                  "the control has held the tape (XOFF) for " +
                      std::to_string(options_.xoff_timeout.count()) + " ms" + sent_note(),
                  {program_.name(), static_cast<int>(last_line_), {}});
    }
    report();
    return service(20ms);
  }

  // A program still being written may keep its next block a while (its first: the whole
  // plan's preparation). The control and the inbox are served meanwhile: a stop is taken at
  // once, and a DC3 or DC1 is heard.
  Expected<void> wait_for_program() {
    while (!program_.ready(0ms)) {
      SUBFEED_TRY(service(20ms));
    }
    return {};
  }

  // A DC1 already heard (while waiting for the program) is the request.
  Expected<void> wait_for_request() {
    observer_.phase("waiting for the control to request the tape (DC1)");
    const auto deadline = Clock::now() + options_.request_timeout;
    while (!requested_) {
      if (Clock::now() > deadline) {
        return fail(ErrorCode::machine_fault,
                    "the control did not request the tape (DC1) within " +
                        std::to_string(options_.request_timeout.count()) + " ms",
                    {link_.name(), 0, {}});
      }
      SUBFEED_TRY(service(20ms));
    }
    paused_ = false;
    return {};
  }

  // Waits up to `timeout` for the control or the inbox, and handles what arrived.
  Expected<void> service(Clock::duration timeout) {
    pollfd fds[2] = {{link_.poll_fd(), POLLIN, 0}, {inbox_ ? inbox_->fd() : -1, POLLIN, 0}};
    const auto ns =
        std::chrono::duration_cast<std::chrono::nanoseconds>(std::max(timeout, Clock::duration(0)));
    const timespec wait{static_cast<time_t>(ns.count() / 1'000'000'000),
                        static_cast<long>(ns.count() % 1'000'000'000)};
    ::ppoll(fds, inbox_ ? 2 : 1, &wait, nullptr);
    if (fds[0].revents != 0) {
      char buffer[64];
      auto n = link_.read(buffer, 0ms);
      if (!n) {
        return lost(n.error().message);
      }
      for (std::size_t i = 0; i < *n; ++i) {
        on_control_byte(buffer[i]);
      }
    }
    if (inbox_ != nullptr && fds[1].revents != 0) {
      for (const ControlCommand& command : inbox_->take()) {
        if (command.kind == ControlCommand::Kind::stop) {
          return fail(ErrorCode::stopped,
                      "stopped by the user" + sent_note() +
                          "; the control runs the blocks it holds, then waits for more",
                      {program_.name(), static_cast<int>(last_line_), {}});
        }
      }
    }
    return {};
  }

  void on_control_byte(char c) {
    if (c == dc3 && !paused_) {
      observer_.link_event("xoff", "");
      paused_ = true;
      paused_since_ = Clock::now();
      ++xoff_count_;
    } else if (c == dc1) {
      if (paused_) {
        observer_.link_event("xon", "");
      }
      paused_ = false;
      requested_ = true;
    }
  }

  std::unexpected<Error> lost(const std::string& why) {
    return fail(ErrorCode::machine_fault, why + " (" + link_.name() + ")" + sent_note(),
                {program_.name(), static_cast<int>(last_line_), {}});
  }

  [[nodiscard]] std::string sent_note() const {
    return last_line_ > 0 ? "; last block sent: line " + std::to_string(last_line_)
                          : "; no block of the file was sent";
  }

  void report() {
    StreamProgress p;
    p.lines_total = total_;
    p.lines_sent = p.lines_acked = blocks_sent_;
    p.bytes_sent = bytes_sent_;
    p.elapsed_s = std::chrono::duration<double>(Clock::now() - start_).count();
    p.link_state = paused_ ? "XOFF" : "send";
    observer_.progress(p);
  }

  Transport& link_;
  BlockSource& program_;
  const FanucStreamOptions& options_;
  ControlInbox* inbox_;
  StreamObserver& observer_;
  const char eob_;
  Clock::duration character_time_{};
  long chunk_ = 1;
  Clock::time_point start_{}, next_at_{}, paused_since_{};
  long total_ = 0, blocks_sent_ = 0, bytes_sent_ = 0, last_line_ = 0, xoff_count_ = 0;
  bool paused_ = false;
  bool requested_ = false;
};

} // namespace

SerialOptions dnc_port_options(const SerialOptions& serial) {
  SerialOptions port = serial;
  const bool hardware = serial.flow == SerialFlow::rts_cts || serial.flow == SerialFlow::both;
  port.flow = hardware ? SerialFlow::rts_cts : SerialFlow::none;
  return port;
}

int bits_per_character(const SerialOptions& serial) {
  return 1 + serial.data_bits + (serial.parity == SerialParity::none ? 0 : 1) + serial.stop_bits;
}

Expected<StreamSummary> stream_fanuc(Transport& link, BlockSource& program,
                                     const FanucStreamOptions& options, ControlInbox* inbox,
                                     StreamObserver& observer) {
  FanucStreamer streamer(link, program, options, inbox, observer);
  return streamer.run();
}

} // namespace subfeed::drivers
