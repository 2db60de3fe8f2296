#include "sim/grbl_sim.hpp"

#include "grbl_codes.hpp"

#include "sim/delivery_hash.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <deque>
#include <fstream>
#include <map>
#include <random>

namespace subfeed::sim {

namespace {

using Clock = std::chrono::steady_clock;

// GRBL 1.1 realtime bytes (documented protocol constants, kept apart from the
// sender's on purpose).
constexpr unsigned char rt_status = '?';
constexpr unsigned char rt_hold = '!';
constexpr unsigned char rt_resume = '~';
constexpr unsigned char rt_reset = 0x18;

std::string strip_line(std::string_view raw) {
  std::string out;
  bool paren = false;
  for (const char c : raw) {
    if (paren) {
      paren = c != ')';
    } else if (c == '(') {
      paren = true;
    } else if (c == ';') {
      break;
    } else if (c != ' ' && c != '\t') {
      out += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    }
  }
  return out;
}

} // namespace

std::vector<std::pair<int, std::string>> default_grbl_settings() {
  return {{0, "10"},        {1, "25"},        {2, "0"},         {3, "0"},         {4, "0"},
          {5, "0"},         {6, "0"},         {10, "1"},        {11, "0.010"},    {12, "0.002"},
          {13, "0"},        {20, "0"},        {21, "0"},        {22, "0"},        {23, "0"},
          {24, "25.000"},   {25, "500.000"},  {26, "250"},      {27, "1.000"},    {30, "1000"},
          {31, "0"},        {32, "0"},        {100, "250.000"}, {101, "250.000"}, {102, "250.000"},
          {110, "500.000"}, {111, "500.000"}, {112, "500.000"}, {120, "10.000"},  {121, "10.000"},
          {122, "10.000"},  {130, "200.000"}, {131, "200.000"}, {132, "200.000"}};
}

class GrblSim::Machine {
public:
  Machine(std::unique_ptr<ByteChannel> channel, GrblSimOptions options)
      : channel_(std::move(channel)), options_(std::move(options)),
        interpreter_(options_.axes, options_.work_offset),
        // GRBL keeps one planner block spare.
        planner_(options_.planner_blocks - 1, options_.motion), rng_(options_.faults.seed),
        record_(options_.record) {
    for (const auto& [key, value] : default_grbl_settings()) {
      settings_[key] = value;
    }
    record_.restore(planner_);
    alarm_locked_ = options_.alarm_on_boot;
  }

  [[nodiscard]] std::string address() const { return channel_->address(); }

  void run(const std::stop_token& stop) {
    last_tick_ = Clock::now();
    while (!stop.stop_requested()) {
      const bool busy = !planner_.empty() || !outgoing_.empty() || !wire_out_.empty() ||
                        has_complete_line() || booting_until_;
      pump_input(busy ? std::chrono::milliseconds(1) : std::chrono::milliseconds(10));
      const auto now = Clock::now();
      tick(std::chrono::duration<double>(now - last_tick_).count());
      last_tick_ = now;
      finish_boot();
      process_lines();
      flush_output();
    }
  }

  [[nodiscard]] GrblSimStats stats() const {
    const std::lock_guard lock(mutex_);
    GrblSimStats copy = stats_;
    copy.state = state_name();
    copy.check_mode = check_mode_;
    copy.starvations = planner_.starvations();
    copy.waiting = program_lines_in_rx(copy.waiting_count);
    return copy;
  }

private:
  // ---- the wire ---------------------------------------------------------------------------

  void pump_input(std::chrono::milliseconds timeout) {
    std::size_t allowed = 4096;
    if (options_.baud > 0) {
      const auto now = Clock::now();
      tokens_ = std::min(256.0, tokens_ + std::chrono::duration<double>(now - last_pump_).count() *
                                              options_.baud / 10.0);
      last_pump_ = now;
      allowed = static_cast<std::size_t>(tokens_);
      if (allowed == 0) {
        std::this_thread::sleep_for(std::chrono::microseconds(200));
        return;
      }
    }
    char buffer[4096];
    const auto n =
        channel_->read(std::span<char>(buffer, std::min(allowed, sizeof buffer)), timeout);
    if (channel_->connected() && !was_connected_) {
      on_connect();
    }
    was_connected_ = channel_->connected();
    if (n && *n < allowed) {
      tokens_ = 0.0; // the wire went idle: idle time is not credit for a later burst
    }
    if (!n || *n == 0) {
      return;
    }
    tokens_ = std::max(0.0, tokens_ - static_cast<double>(*n));
    const std::lock_guard lock(mutex_);
    for (std::size_t i = 0; i < *n; ++i) {
      on_byte(static_cast<unsigned char>(buffer[i]));
    }
  }

  // An Arduino-based GRBL resets whenever its port is opened (DTR); grblHAL on native USB
  // does not, and says nothing until spoken to.
  void on_connect() {
    if (!options_.grblhal) {
      const std::lock_guard lock(mutex_);
      booting_until_ = Clock::now() + options_.boot_time;
    }
  }

  void finish_boot() {
    if (booting_until_ && Clock::now() >= *booting_until_) {
      booting_until_.reset();
      const std::lock_guard lock(mutex_);
      power_up();
    }
  }

  void on_byte(unsigned char c) {
    if (booting_until_ || frozen_) {
      return; // the bootloader is running: nothing reaches the firmware
    }
    if (c == rt_status || c == rt_hold || c == rt_resume || c == rt_reset || c >= 0x80) {
      on_realtime(c);
      return;
    }
    if (static_cast<int>(rx_.size()) >= options_.rx_buffer) {
      ++stats_.overrun_bytes; // the firmware's ring buffer is full: the byte is lost
      return;
    }
    rx_.push_back(static_cast<char>(c));
    stats_.max_rx_fill = std::max(stats_.max_rx_fill, static_cast<int>(rx_.size()));
  }

  void on_realtime(unsigned char c) {
    switch (c) {
    case rt_status:
      ++stats_.status_queries;
      send(status_report());
      break;
    case rt_hold:
      ++stats_.feed_holds;
      if (last_error_written_) {
        stats_.error_to_hold_ms.push_back(
            std::chrono::duration<double, std::milli>(Clock::now() - *last_error_written_).count());
        last_error_written_.reset();
      }
      if (!holding_ && !alarm_locked_) {
        holding_ = true;
        hold_done_at_ = Clock::now() +
                        std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(
                            planner_.stop_seconds() / options_.motion.speed));
      }
      break;
    case rt_resume:
      if (holding_ && hold_complete()) {
        holding_ = false;
      }
      break;
    case rt_reset:
      ++stats_.resets;
      soft_reset();
      break;
    default:
      if (c >= 0x90 && c <= 0x9D) {
        ++stats_.overrides;
        stats_.override_times.push_back(Clock::now());
        apply_override(c);
      }
      break; // other extended bytes: realtime commands this model ignores, never buffered
    }
  }

  void apply_override(unsigned char c) {
    switch (c) {
    case 0x90:
      feed_override_ = 100;
      break;
    case 0x91:
      feed_override_ = std::min(200, feed_override_ + 10);
      break;
    case 0x92:
      feed_override_ = std::max(10, feed_override_ - 10);
      break;
    case 0x93:
      feed_override_ = std::min(200, feed_override_ + 1);
      break;
    case 0x94:
      feed_override_ = std::max(10, feed_override_ - 1);
      break;
    case 0x95:
      rapid_override_ = 100;
      break;
    case 0x96:
      rapid_override_ = 50;
      break;
    case 0x97:
      rapid_override_ = 25;
      break;
    default:
      spindle_override_ = c == 0x99 ? 100 : spindle_override_; // spindle: recorded only
      break;
    }
    override_changed_ = true;
  }

  // ---- machine state ----------------------------------------------------------------------

  [[nodiscard]] bool hold_complete() const { return holding_ && Clock::now() >= hold_done_at_; }
  [[nodiscard]] bool moving() const { return !planner_.empty() && !hold_complete(); }

  [[nodiscard]] std::string state_name() const {
    if (alarm_locked_) {
      return "Alarm";
    }
    if (holding_) {
      return hold_complete() ? "Hold:0" : "Hold:1";
    }
    if (check_mode_) {
      return "Check";
    }
    return planner_.empty() ? "Idle" : "Run";
  }

  void tick(double seconds) {
    const double scale = feed_override_ / 100.0;
    const std::lock_guard lock(mutex_);
    const auto finished = planner_.advance(seconds * scale, hold_complete());
    record_.advanced(planner_, finished);
    const auto& alarm_after = options_.faults.alarm_after_s;
    if (alarm_after && first_program_line_at_ && !alarm_fired_ &&
        Clock::now() - *first_program_line_at_ >= std::chrono::duration<double>(*alarm_after)) {
      alarm_fired_ = true;
      raise_alarm(options_.faults.alarm_code);
    }
  }

  void drop_queue() {
    planner_.clear();
    record_.dropped();
  }

  void raise_alarm(int code) {
    drop_queue();
    drop_rx();
    holding_ = false;
    alarm_locked_ = true;
    critical_ = true; // nothing more is read until a reset
    ++stats_.alarms_sent;
    send("ALARM:" + std::to_string(code));
    send("[MSG:Reset to continue]");
  }

  void power_up() {
    drop_rx();
    drop_queue();
    interpreter_.reset();
    holding_ = false;
    check_mode_ = false;
    critical_ = false;
    latched_error_ = 0;
    skip_lf_ = false;
    feed_override_ = rapid_override_ = spindle_override_ = 100;
    send(options_.grblhal ? "GrblHAL 1.1f ['$' or '$HELP' for help]" : "Grbl 1.1h ['$' for help]");
    if (alarm_locked_) {
      send("[MSG:'$H'|'$X' to unlock]");
    }
  }

  void soft_reset() {
    if (moving()) {
      alarm_locked_ = true; // steps were lost: the position can no longer be trusted
      ++stats_.alarms_sent;
      send("ALARM:" + std::to_string(grbl_code::alarm_reset_in_motion));
    }
    outgoing_.clear();
    wire_out_.clear();
    error_ends_.clear();
    power_up();
  }

  // ---- lines ------------------------------------------------------------------------------

  // The program lines (not `$` commands, not blank) in the RX buffer, a line cut short at its
  // end included; `count` gets how many, the texts are kept only when recording.
  std::vector<std::string> program_lines_in_rx(long& count) const {
    std::vector<std::string> lines;
    count = 0;
    std::string raw;
    for (std::size_t i = 0; i <= rx_.size(); ++i) {
      if (i < rx_.size() && rx_[i] != '\n' && rx_[i] != '\r') {
        raw += rx_[i];
        continue;
      }
      const std::string line = strip_line(raw);
      raw.clear();
      if (!line.empty() && line[0] != '$') {
        ++count;
        if (options_.record_executed) {
          lines.push_back(line);
        }
      }
    }
    return lines;
  }

  // A reset, an alarm or an EEPROM write empties the RX buffer unread.
  void drop_rx() {
    long count = 0;
    auto lines = program_lines_in_rx(count);
    drop_lines(std::move(lines), count);
    rx_.clear();
  }

  void drop_lines(std::vector<std::string> lines, long count) {
    stats_.dropped_count += count;
    stats_.dropped.insert(stats_.dropped.end(), std::make_move_iterator(lines.begin()),
                          std::make_move_iterator(lines.end()));
  }

  // A program line answered with an error: received, not run.
  void refuse(const std::string& line, int code) {
    ++stats_.refused_count;
    if (options_.record_executed) {
      stats_.refused.push_back(line);
    }
    reply_error(code);
  }

  [[nodiscard]] bool has_complete_line() const {
    return std::ranges::find_if(rx_, [](char c) { return c == '\n' || c == '\r'; }) != rx_.end();
  }

  void process_lines() {
    const std::lock_guard lock(mutex_);
    while (!critical_ && !frozen_ && has_complete_line() && !planner_.full()) {
      const auto end = std::ranges::find_if(rx_, [](char c) { return c == '\n' || c == '\r'; });
      const bool lf = *end == '\n';
      std::string raw(rx_.begin(), end);
      rx_.erase(rx_.begin(), end + 1);
      if (skip_lf_ && lf && raw.empty()) { // grblHAL: the LF of a CRLF is not a second line
        skip_lf_ = false;
        continue;
      }
      skip_lf_ = options_.grblhal && !lf;
      execute_line(raw);
    }
  }

  void execute_line(const std::string& raw) {
    const std::string line = strip_line(raw);
    if (line.empty()) {
      latched_error_ = 0;
      reply_ok();
      return;
    }
    if (static_cast<int>(line.size()) > options_.line_limit) {
      count_program_line(line);
      refuse(line, grbl_code::line_overflow);
      return;
    }
    if (line[0] == '$') {
      latched_error_ = 0;
      execute_system(line);
      return;
    }
    execute_gcode(line);
  }

  void count_program_line(const std::string& line) {
    ++stats_.program_lines;
    if (!first_program_line_at_) {
      first_program_line_at_ = Clock::now();
    }
    (void)line;
  }

  // Writing EEPROM stops the AVR's serial interrupt: bytes arriving meanwhile are lost.
  void eeprom_write() {
    if (!rx_.empty()) {
      ++stats_.eeprom_violations;
      drop_rx();
    }
  }

  void execute_gcode(const std::string& line) {
    count_program_line(line);
    const long number = stats_.program_lines;
    const auto& f = options_.faults;
    if (f.disconnect_on_line && number == *f.disconnect_on_line) {
      drop_lines(recorded(line), 1);
      channel_->close();
      return;
    }
    if (f.freeze_on_line && number == *f.freeze_on_line) {
      drop_lines(recorded(line), 1);
      frozen_ = true;
      return;
    }
    if (f.reset_on_line && number == *f.reset_on_line) {
      drop_lines(recorded(line), 1); // the brown-out took it before it ran
      power_up();
      return;
    }
    if (f.garbage_on_line && number == *f.garbage_on_line) {
      send(std::string("\xfe\xff#@!") + '\x07' + "~~");
    }
    if (alarm_locked_) {
      refuse(line, grbl_code::locked);
      return;
    }
    if (latched_error_ != 0) {
      refuse(line, latched_error_);
      return;
    }
    if (f.error_on_line && number == *f.error_on_line) {
      refuse(line, f.error_code);
      return;
    }
    const SimLineResult result = interpreter_.execute(line, planner_.planned_end());
    if (result.error != 0) {
      refuse(line, result.error);
      return;
    }
    if (check_mode_) {
      ++stats_.checked_lines;
      reply_ok();
      return;
    }
    if (result.writes_eeprom) {
      eeprom_write();
    }
    if (result.move.present) {
      planner_.push(result.move);
    } else if (result.dwell_s > 0.0) {
      planner_.push_dwell(result.dwell_s);
    }
    record_executed(line, result.move.present || result.dwell_s > 0.0);
    if (f.lose_ack_on_line && number == *f.lose_ack_on_line) {
      return;
    }
    reply_ok();
  }

  [[nodiscard]] std::vector<std::string> recorded(const std::string& line) const {
    return options_.record_executed ? std::vector<std::string>{line} : std::vector<std::string>{};
  }

  void record_executed(const std::string& line, bool queued_move) {
    ++stats_.executed_count;
    stats_.executed_hash = delivery_hash(stats_.executed_hash, line);
    if (options_.record_executed) {
      stats_.executed.push_back(line);
    }
    record_.accepted(line, queued_move);
  }

  [[nodiscard]] bool idle_or_alarm() const { return !holding_ && planner_.empty(); }

  void execute_system(const std::string& line) {
    if (line == "$$") {
      return idle_or_alarm() ? dump_settings() : reply_error(grbl_code::not_idle);
    }
    if (line == "$I") {
      return idle_or_alarm() ? build_info() : reply_error(grbl_code::not_idle);
    }
    if (line == "$C") {
      return toggle_check_mode();
    }
    if (line == "$X") {
      alarm_locked_ = false;
      send("[MSG:Caution: Unlocked]");
      return reply_ok();
    }
    if (line == "$G") {
      send("[GC:G0 G54 G17 G21 G90 G94 M5 M9 T0 F0 S0]");
      return reply_ok();
    }
    if (line == "$H") {
      return reply_error(settings_[22] == "0" ? grbl_code::homing_disabled : 0);
    }
    if (line == "$#") {
      send("[G54:0.000,0.000,0.000]");
      send("[TLO:0.000]");
      return reply_ok();
    }
    if (line == "$N") {
      send("$N0=");
      send("$N1=");
      return reply_ok();
    }
    write_setting(line);
  }

  void write_setting(const std::string& line) {
    const auto eq = line.find('=');
    if (eq == std::string::npos || !idle_or_alarm()) {
      return reply_error(eq == std::string::npos ? grbl_code::invalid_statement
                                                 : grbl_code::not_idle);
    }
    const std::string key = line.substr(1, eq - 1);
    eeprom_write();
    if (key.starts_with("N") || key == "I" || key == "RST") {
      return reply_ok(); // startup lines, build info, restore: stored, nothing to model
    }
    int number = 0;
    if (std::sscanf(key.c_str(), "%d", &number) != 1 || !settings_.contains(number)) {
      return reply_error(grbl_code::invalid_statement);
    }
    settings_[number] = line.substr(eq + 1);
    reply_ok();
  }

  void dump_settings() {
    for (const auto& [key, value] : settings_) {
      send("$" + std::to_string(key) + "=" + value);
    }
    reply_ok();
  }

  void build_info() {
    send(options_.grblhal ? "[VER:1.1f.20230610:]" : "[VER:1.1h.20190825:]");
    if (options_.report_build_options) {
      const std::string blocks = std::to_string(options_.planner_blocks - 1);
      const std::string rx = std::to_string(options_.rx_buffer);
      send(options_.grblhal
               ? "[OPT:VNML+," + blocks + "," + rx + "," + std::to_string(options_.axes) + ",0]"
               : "[OPT:V," + blocks + "," + rx + "]");
    }
    if (options_.grblhal) {
      send("[AXS:" + std::to_string(options_.axes) + ":" +
           std::string("XYZABC").substr(0, static_cast<std::size_t>(options_.axes)) + "]");
      send("[NEWOPT:ENUMS,RT+,HOME,TC]");
      send("[FIRMWARE:grblHAL]");
    }
    reply_ok();
  }

  void toggle_check_mode() {
    if (check_mode_) {
      send("[MSG:Disabled]");
      reply_ok();
      check_mode_ = false;
      power_up(); // leaving check mode resets the controller
      return;
    }
    if (!idle_or_alarm() || alarm_locked_) {
      return reply_error(grbl_code::not_idle);
    }
    check_mode_ = true;
    send("[MSG:Enabled]");
    reply_ok();
  }

  // ---- output -----------------------------------------------------------------------------

  void reply_ok() { send("ok"); }

  void reply_error(int code) {
    if (code == 0) {
      return reply_ok();
    }
    ++stats_.errors_sent;
    if (options_.grblhal) {
      latched_error_ = code;
    }
    send("error:" + std::to_string(code));
  }

  void send(std::string text) {
    auto release = Clock::now();
    if (options_.faults.max_ack_delay.count() > 0) {
      std::uniform_int_distribution<long> delay(0, options_.faults.max_ack_delay.count());
      release += std::chrono::milliseconds(delay(rng_));
      if (!outgoing_.empty()) {
        release = std::max(release, outgoing_.back().first); // replies keep their order
      }
    }
    outgoing_.emplace_back(release, std::move(text) + "\r\n");
  }

  // Replies leave at the wire speed too: the link is full duplex, each direction at `baud`.
  void flush_output() {
    {
      const std::lock_guard lock(mutex_);
      const auto now = Clock::now();
      while (!outgoing_.empty() && outgoing_.front().first <= now) {
        wire_out_ += outgoing_.front().second;
        if (outgoing_.front().second.starts_with("error:")) {
          error_ends_.push_back(out_queued_ + static_cast<long>(wire_out_.size()));
        }
        outgoing_.pop_front();
      }
    }
    std::size_t allowed = wire_out_.size();
    if (options_.baud > 0) {
      const auto now = Clock::now();
      out_tokens_ =
          std::min(64.0, out_tokens_ + std::chrono::duration<double>(now - last_flush_).count() *
                                           options_.baud / 10.0);
      last_flush_ = now;
      allowed = std::min(allowed, static_cast<std::size_t>(out_tokens_));
    }
    if (allowed == 0) {
      return;
    }
    (void)channel_->write_all(std::string_view(wire_out_).substr(0, allowed));
    out_tokens_ -= static_cast<double>(allowed);
    wire_out_.erase(0, allowed);
    if (wire_out_.empty()) {
      out_tokens_ = 0.0;
    }
    out_queued_ += static_cast<long>(allowed);
    const std::lock_guard lock(mutex_);
    while (!error_ends_.empty() && error_ends_.front() <= out_queued_) {
      error_ends_.pop_front();
      last_error_written_ = Clock::now();
    }
  }

  [[nodiscard]] std::string status_report() {
    const std::string state = state_name();
    stats_.status_states.push_back(state);
    const auto& p = planner_.position();
    std::string report = "<" + state + (options_.report_wpos ? "|WPos:" : "|MPos:");
    char number[32];
    for (int a = 0; a < options_.axes; ++a) {
      const auto i = static_cast<std::size_t>(a);
      std::snprintf(number, sizeof number, "%s%.3f", a == 0 ? "" : ",",
                    p[i] - (options_.report_wpos ? options_.work_offset[i] : 0.0));
      report += number;
    }
    report += "|Bf:" + std::to_string(planner_.free_blocks()) + "," +
              std::to_string(options_.rx_buffer - static_cast<int>(rx_.size()));
    std::snprintf(number, sizeof number, "|FS:%.0f,0", planner_.current_feed_mm_min());
    report += number;
    if (++status_count_ % 10 == 0) {
      report += "|WCO:";
      for (int a = 0; a < options_.axes; ++a) {
        std::snprintf(number, sizeof number, "%s%.3f", a == 0 ? "" : ",",
                      options_.work_offset[static_cast<std::size_t>(a)]);
        report += number;
      }
    }
    if (override_changed_ || status_count_ % 10 == 5) {
      override_changed_ = false;
      report += "|Ov:" + std::to_string(feed_override_) + "," + std::to_string(rapid_override_) +
                "," + std::to_string(spindle_override_);
    }
    return report + ">";
  }

  std::unique_ptr<ByteChannel> channel_;
  GrblSimOptions options_;
  GcodeInterpreter interpreter_;
  MotionPlanner planner_;
  std::deque<char> rx_;
  std::deque<std::pair<Clock::time_point, std::string>> outgoing_;
  std::string wire_out_;        // released replies not yet on the wire
  std::deque<long> error_ends_; // output offsets at which an error reply has fully left
  long out_queued_ = 0;         // bytes written to the wire so far
  double out_tokens_ = 0.0;
  Clock::time_point last_flush_ = Clock::now();
  std::map<int, std::string> settings_;
  std::mt19937 rng_;
  MachineRecord record_;
  mutable std::mutex mutex_;
  GrblSimStats stats_;

  Clock::time_point last_tick_{};
  Clock::time_point last_pump_ = Clock::now();
  Clock::time_point hold_done_at_{};
  std::optional<Clock::time_point> first_program_line_at_;
  std::optional<Clock::time_point> booting_until_;
  std::optional<Clock::time_point> last_error_written_;
  double tokens_ = 0.0;
  bool was_connected_ = false;
  bool holding_ = false;
  bool check_mode_ = false;
  bool alarm_locked_ = false;
  bool critical_ = false;
  bool alarm_fired_ = false;
  bool frozen_ = false;
  bool skip_lf_ = false;
  bool override_changed_ = false;
  int latched_error_ = 0;
  int status_count_ = 0;
  int feed_override_ = 100;
  int rapid_override_ = 100;
  int spindle_override_ = 100;
};

GrblSim::GrblSim(std::unique_ptr<ByteChannel> channel, GrblSimOptions options)
    : machine_(std::make_unique<Machine>(std::move(channel), std::move(options))),
      address_(machine_->address()) {}

GrblSim::~GrblSim() {
  stop();
}

void GrblSim::start() {
  thread_.start([this](const std::stop_token& stop) { machine_->run(stop); });
}

void GrblSim::stop() {
  thread_.stop();
}

void GrblSim::run(const std::stop_token& stop) {
  machine_->run(stop);
}

GrblSimStats GrblSim::stats() const {
  return machine_->stats();
}

} // namespace subfeed::sim
