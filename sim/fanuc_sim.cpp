#include "sim/fanuc_sim.hpp"

#include "sim/delivery_hash.hpp"

#include "sim/gcode_interpreter.hpp"
#include "sim/pty.hpp"

#include <algorithm>
#include <cctype>
#include <deque>
#include <mutex>
#include <random>
#include <termios.h>

namespace subfeed::sim {

namespace {

using Clock = std::chrono::steady_clock;

constexpr char dc1 = 0x11; // XON: start reader
constexpr char dc3 = 0x13; // XOFF: stop reader

// ISO 840 tape characters a Fanuc control reads without a TH alarm.
bool iso840(unsigned char c) {
  return (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == ' ' || c == '+' || c == '-' ||
         c == '.' || c == '/' || c == '(' || c == ')' || c == '#' || c == '*' || c == ';' ||
         c == '=' || c == '%' || c == ':' || c == '\n' || c == '\r' || c == 0;
}

std::string interpretable(const std::string& block) {
  std::string out;
  bool comment = false;
  for (const char c : block) {
    if (comment) {
      comment = c != ')';
    } else if (c == '(') {
      comment = true;
    } else if (c != ' ') {
      out += c;
    }
  }
  return out;
}

} // namespace

class FanucSim::Control {
public:
  Control(std::unique_ptr<ByteChannel> channel, FanucSimOptions options)
      : channel_(std::move(channel)), options_(std::move(options)), interpreter_(6),
        planner_(options_.look_ahead_blocks, options_.motion), record_(options_.record),
        rng_(options_.seed) {
    record_.restore(planner_);
  }

  [[nodiscard]] std::string address() const { return channel_->address(); }

  void run(const std::stop_token& stop) {
    auto last = Clock::now();
    while (!stop.stop_requested()) {
      pump_input();
      const auto now = Clock::now();
      const std::lock_guard lock(mutex_);
      const auto finished =
          planner_.advance(std::chrono::duration<double>(now - last).count(), false);
      last = now;
      record_.advanced(planner_, finished);
      execute_blocks();
      release_flow();
      flush_output();
    }
  }

  [[nodiscard]] FanucSimStats stats() const {
    const std::lock_guard lock(mutex_);
    return stats_;
  }

private:
  [[nodiscard]] int bits_per_char() const {
    return 1 + options_.data_bits + (options_.parity == 'N' ? 0 : 1) + options_.stop_bits;
  }

  // Checked before each read: what the link holds when the latency window closes was
  // written inside it.
  void close_latency_window() {
    const std::lock_guard lock(mutex_);
    if (!latency_closed_ && Clock::now() >= latency_ends_) {
      latency_closed_ = true;
      in_flight_ = channel_->unread();
    }
  }

  void pump_input() {
    close_latency_window();
    std::size_t allowed = 4096;
    if (options_.baud > 0) {
      const auto now = Clock::now();
      tokens_ +=
          std::chrono::duration<double>(now - last_pump_).count() * options_.baud / bits_per_char();
      // A stalled control thread catches up with what the wire delivered meanwhile (a UART
      // does not lag); an idle wire banks nothing (reset below when the input drains).
      tokens_ = std::min(tokens_, 4096.0);
      last_pump_ = now;
      allowed = static_cast<std::size_t>(tokens_);
    }
    char buffer[4096];
    const auto n =
        channel_->read(std::span<char>(buffer, std::min(allowed, sizeof buffer)),
                       allowed == 0 ? std::chrono::milliseconds(0) : std::chrono::milliseconds(1));
    if (allowed == 0) {
      std::this_thread::sleep_for(std::chrono::microseconds(100));
    }
    const std::lock_guard lock(mutex_);
    if (channel_->connected() && !connected_) {
      on_connect();
    }
    connected_ = channel_->connected();
    if (!n || *n == 0) {
      if (n && *n < allowed) {
        tokens_ = 0.0; // an idle wire banks no time
      }
      return;
    }
    if (*n < allowed) {
      tokens_ = 0.0;
    } else {
      tokens_ -= static_cast<double>(*n);
    }
    for (std::size_t i = 0; i < *n; ++i) {
      batch_left_ = *n - i - 1;
      on_byte(static_cast<unsigned char>(buffer[i]));
    }
    batch_left_ = 0;
  }

  void on_connect() {
    framing_checked_ = false; // judged on the first character, once the sender has set up its port
    if (options_.request_tape) {
      out_ += dc1; // the control asks for the tape
    }
  }

  // The pty master sees the slave's settings: a sender framing bytes differently from the
  // control garbles characters (TH alarms on a real line). Linux forces 8 data bits and no
  // parity on every pty, so of the framing only the stop bits can be compared here.
  void check_framing() {
    const auto* pty = dynamic_cast<const Pty*>(channel_.get());
    termios tio{};
    if (pty == nullptr || ::tcgetattr(pty->master_fd(), &tio) != 0) {
      return;
    }
    const int stop = (tio.c_cflag & CSTOPB) != 0 ? 2 : 1;
    if (stop != options_.stop_bits) {
      raise("TH framing: sender " + std::to_string(stop) + " stop bit(s), control " +
            std::to_string(options_.stop_bits));
    }
  }

  void raise(const std::string& alarm) {
    if (stats_.alarm.empty()) {
      stats_.alarm = alarm;
      out_ += dc3; // an alarmed control stops the reader
    }
  }

  void on_byte(unsigned char c) {
    if (!framing_checked_) {
      framing_checked_ = true;
      check_framing();
    }
    if (!stats_.alarm.empty()) {
      return;
    }
    if (xoff_active_ && !in_flight()) {
      if (++after_xoff_ > options_.overrun_tolerance) {
        raise("087 overrun: " + std::to_string(after_xoff_) + " characters after DC3");
      }
    }
    stats_.max_after_xoff = std::max(stats_.max_after_xoff, after_xoff_);
    if (!iso840(c)) {
      std::string shown = std::isprint(c) != 0 ? std::string(1, static_cast<char>(c))
                                               : "0x" + std::to_string(static_cast<int>(c));
      raise("TH character '" + shown + "'");
      return;
    }
    // Once DC3 is out, the count above judges the sender. What was already in flight when
    // it left arrived while this control (a thread, not a UART interrupt) was not looking:
    // a real control would have sent DC3 as the mark was passed, so those characters may
    // overfill the buffer here without an alarm.
    if (static_cast<int>(buffer_.size()) >= options_.buffer && !xoff_active_) {
      raise("087 overrun: buffer full");
      return;
    }
    buffer_.push_back(static_cast<char>(c));
    stats_.max_fill = std::max(stats_.max_fill, static_cast<int>(buffer_.size()));
    if (static_cast<int>(buffer_.size()) >= options_.high_water && !xoff_active_) {
      send_xoff();
    }
  }

  // Whether this character, read while DC3 holds, was on its way before the sender could
  // know: written before the DC3 left, or within the link's latency after it.
  bool in_flight() {
    if (!latency_closed_) {
      return true;
    }
    if (in_flight_ == 0) {
      return false;
    }
    --in_flight_;
    return true;
  }

  // The DC3 leaves at once, as from a UART interrupt. What the sender had written by then,
  // read or not (the rest of this read, and the pty's backlog when this thread ran late),
  // was on the wire before the DC3 and is not held against it.
  void send_xoff() {
    out_ += dc3;
    flush_output();
    xoff_active_ = true;
    in_flight_ = batch_left_ + channel_->unread();
    latency_ends_ = Clock::now() + options_.link_latency;
    latency_closed_ = options_.link_latency.count() == 0;
    after_xoff_ = 0;
    ++stats_.xoff_sent;
  }

  void release_flow() {
    if (!xoff_active_ || stuck_ || !stats_.alarm.empty() ||
        static_cast<int>(buffer_.size()) > options_.low_water) {
      return;
    }
    xoff_active_ = false;
    if (lose_next_xon_) {
      lose_next_xon_ = false; // owed and never sent: the sender waits for it in vain
      return;
    }
    out_ += dc1;
    ++stats_.xon_sent;
  }

  void execute_blocks() {
    const char eob = options_.eia_cr ? '\r' : '\n';
    while (!planner_.full() && stats_.alarm.empty() && Clock::now() >= stalled_until_) {
      const auto end = std::ranges::find(buffer_, eob);
      if (end == buffer_.end()) {
        return;
      }
      std::string block(buffer_.begin(), end);
      buffer_.erase(buffer_.begin(), end + 1);
      while (!block.empty() && (block.back() == '\r' || block.back() == '\0')) {
        block.pop_back();
      }
      const auto first = block.find_first_not_of(std::string_view("\0\r\n", 3)); // tape leader
      block.erase(0, first == std::string::npos ? block.size() : first);
      on_block(block);
    }
  }

  void on_block(const std::string& block) {
    if (block.empty()) {
      return;
    }
    if (block == "%") {
      (stats_.program_started ? stats_.program_ended : stats_.program_started) = true;
      return;
    }
    if (!stats_.program_started || stats_.program_ended) {
      return; // outside the program: a control ignores it
    }
    if (stats_.program_number.empty() && (block.front() == 'O' || block.front() == ':')) {
      stats_.program_number = block.substr(1);
      return;
    }
    run_block(block);
  }

  void run_block(const std::string& block) {
    const long number = ++stats_.blocks_received;
    const auto& f = options_.faults;
    if (f.drop_at_block && number == *f.drop_at_block) {
      channel_->close();
      return;
    }
    if (f.stuck_xoff_at_block && number == *f.stuck_xoff_at_block) {
      stuck_ = true;
      if (!xoff_active_) {
        send_xoff();
      }
    }
    if (f.lose_xon_after_block && number == *f.lose_xon_after_block) {
      lose_next_xon_ = true;
    }
    if (options_.max_block_pause.count() > 0 &&
        std::uniform_int_distribution<int>(1, std::max(1, options_.pause_one_in))(rng_) == 1) {
      std::uniform_int_distribution<long> pause(0, options_.max_block_pause.count());
      stalled_until_ = Clock::now() + std::chrono::milliseconds(pause(rng_));
    }
    const SimLineResult result = interpreter_.execute(interpretable(block), planner_.planned_end());
    const bool moves = result.error == 0 && result.move.present;
    if (moves) {
      planner_.push(result.move);
    }
    record_.accepted(block, moves);
    ++stats_.executed_count;
    stats_.executed_hash = delivery_hash(stats_.executed_hash, block);
    if (options_.record_executed) {
      stats_.executed.push_back(block);
    }
  }

  void flush_output() {
    if (!out_.empty()) {
      (void)channel_->write_all(out_);
      out_.clear();
    }
  }

  std::unique_ptr<ByteChannel> channel_;
  FanucSimOptions options_;
  GcodeInterpreter interpreter_;
  MotionPlanner planner_;
  MachineRecord record_;
  std::mt19937 rng_;
  mutable std::mutex mutex_;
  FanucSimStats stats_;
  std::deque<char> buffer_;
  std::string out_;
  Clock::time_point last_pump_ = Clock::now();
  Clock::time_point stalled_until_{};
  double tokens_ = 0.0;
  int after_xoff_ = 0;
  std::size_t batch_left_ = 0;       // bytes of the current read after the one being handled
  std::size_t in_flight_ = 0;        // bytes written before the last DC3 left, not yet handled
  Clock::time_point latency_ends_{}; // the last DC3 left, plus the link's latency
  bool latency_closed_ = true;
  bool connected_ = false;
  bool framing_checked_ = false;
  bool xoff_active_ = false;
  bool stuck_ = false;
  bool lose_next_xon_ = false;
};

FanucSim::FanucSim(std::unique_ptr<ByteChannel> channel, FanucSimOptions options)
    : control_(std::make_unique<Control>(std::move(channel), std::move(options))),
      address_(control_->address()) {}

FanucSim::~FanucSim() {
  stop();
}

void FanucSim::start() {
  thread_.start([this](const std::stop_token& stop) { control_->run(stop); });
}

void FanucSim::stop() {
  thread_.stop();
}

void FanucSim::run(const std::stop_token& stop) {
  control_->run(stop);
}

FanucSimStats FanucSim::stats() const {
  return control_->stats();
}

} // namespace subfeed::sim
