#pragma once
// A simulated GRBL 1.1 (or grblHAL) controller behind a ByteChannel. It behaves like the
// firmware where a sender can tell the difference: welcome banner (on every new connection,
// as an Arduino resets when its port opens), `$I` with [OPT:], `$$`, `$C` check mode, `$X`,
// ok/error:N, ALARM:N, status reports, realtime bytes that bypass the line buffer, a line
// limit (error:11), a serial RX buffer that silently drops what does not fit (every dropped
// byte is counted), a planner queue drained by a motion-time model, and an emulated wire
// speed. Faults can be injected. Everything the sender got right or wrong is in stats().

#include "sim/byte_channel.hpp"
#include "sim/delivery_hash.hpp"
#include "sim/machine_record.hpp"
#include "sim/motion_planner.hpp"
#include "sim/serve_thread.hpp"

#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace subfeed::sim {

struct GrblFaults {
  // Counts are of program lines (G-code, not `$` commands), from 1.
  std::optional<long> error_on_line; // reply error:error_code instead of running it
  int error_code = 20;
  std::optional<double>
      alarm_after_s; // raise ALARM:alarm_code this long after the first program line
  int alarm_code = 1;
  std::optional<long> reset_on_line;          // the controller resets itself (brown-out)
  std::optional<long> disconnect_on_line;     // the link drops
  std::optional<long> garbage_on_line;        // a burst of line noise before the reply
  std::optional<long> lose_ack_on_line;       // the `ok` never comes
  std::optional<long> freeze_on_line;         // the firmware hangs: nothing is answered any more
  std::chrono::milliseconds max_ack_delay{0}; // every reply delayed by up to this (random)
  unsigned seed = 1;
};

struct GrblSimOptions {
  int axes = 3;        // 3..6 (XYZ, then A, B, C)
  int rx_buffer = 128; // bytes
  int planner_blocks = 16;
  int line_limit = 79;      // characters after spaces and comments are removed
  int baud = 115200;        // emulated wire speed, both directions; 0 = unlimited
  bool grblhal = false;     // grblHAL banner, [OPT:] and latching errors
  bool report_wpos = false; // WPos instead of MPos in status reports
  AxisArray work_offset{};  // G54 from the machine's zero: reported as WCO
  // GRBL on an Arduino resets when its port opens and boots for about 1.5 s, dropping what
  // arrives meanwhile, then prints its banner. grblHAL does not reset on connect.
  std::chrono::milliseconds boot_time{50};
  bool report_build_options = true; // false: $I has no [OPT:] line (old or odd firmware)
  bool alarm_on_boot = false;       // boots locked, as GRBL with homing enabled does
  MotionModel motion;
  GrblFaults faults;
  // Keep every executed line in stats (tests); off, memory stays flat however long the job:
  // executed_count and executed_hash still prove delivery.
  bool record_executed = false;
  // The lines carried out and the machine's position, kept beyond the controller.
  MachineRecordOptions record;
};

struct GrblSimStats {
  std::vector<std::string> executed; // accepted program lines, as received (stripped), in order
  long executed_count = 0;
  std::uint64_t executed_hash = delivery_hash_seed; // FNV-1a over executed lines and '\n'
  // Program lines received and not run, as received (stripped), in order; the texts only
  // with record_executed. Refused: answered error:N. Dropped: emptied unread from the RX
  // buffer by a reset, an alarm or an EEPROM write, or taken by a fault (brown-out, hang,
  // lost link) before running; a line cut short at the buffer's end counts. Waiting: in the
  // RX buffer now, unread (behind an alarm, or not yet reached).
  std::vector<std::string> refused, dropped, waiting;
  long refused_count = 0, dropped_count = 0, waiting_count = 0;
  long checked_lines = 0;     // program lines answered in check mode ($C)
  long program_lines = 0;     // program lines received, accepted or not
  long overrun_bytes = 0;     // bytes dropped because the RX buffer was full
  long eeprom_violations = 0; // EEPROM writes while more bytes were waiting
  int max_rx_fill = 0;        // most bytes ever waiting in the RX buffer
  long errors_sent = 0;
  long alarms_sent = 0;
  long resets = 0;                        // soft resets received (0x18)
  long feed_holds = 0;                    // '!' received
  long status_queries = 0;                // '?' received
  long overrides = 0;                     // override bytes received
  std::size_t starvations = 0;            // planner ran dry while lines were still coming
  std::vector<std::string> status_states; // every state reported, in order
  // For latency measurements: milliseconds from writing an error:N reply to receiving the
  // sender's feed hold, and when each override byte arrived.
  std::vector<double> error_to_hold_ms;
  std::vector<std::chrono::steady_clock::time_point> override_times;
  std::string state; // state now
  bool check_mode = false;
};

class GrblSim {
public:
  GrblSim(std::unique_ptr<ByteChannel> channel, GrblSimOptions options);
  GrblSim(const GrblSim&) = delete;
  GrblSim& operator=(const GrblSim&) = delete;
  ~GrblSim();

  // Serves on a thread of its own until stop() or destruction.
  void start();
  void stop();
  // Serves on the calling thread until `stop` is requested.
  void run(const std::stop_token& stop);

  [[nodiscard]] std::string address() const { return address_; }
  [[nodiscard]] GrblSimStats stats() const;

private:
  class Machine;
  std::unique_ptr<Machine> machine_;
  std::string address_;
  ServeThread thread_; // last: stops before the machine it runs goes
};

// The GRBL settings the simulator reports and lets a sender change with $n=v.
[[nodiscard]] std::vector<std::pair<int, std::string>> default_grbl_settings();

} // namespace subfeed::sim
