// subfeed-sim: simulated controllers on a pty (or TCP), for dry runs and tests. Each
// protocol is a subcommand; the address a sender connects to (a tty path, or host:port) is
// printed on stdout and the simulator serves until it is sent SIGINT or SIGTERM.

#include "base/number_text.hpp"
#include "sim/fanuc_sim.hpp"
#include "sim/grbl_sim.hpp"
#include "sim/pty.hpp"
#include "sim/tcp_listener.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <csignal>
#include <iostream>

namespace {

using namespace subfeed::sim;

// Refusals as one plain sentence; CLI11's PositiveNumber prints its range up to 1.8e308.
CLI::Validator positive_number() {
  return {[](std::string& text) { return subfeed::positive_number_problem(text, false); }, "> 0"};
}

// Opens --machine-state if given; false (having said why) when it cannot be used.
bool open_machine_state(const std::string& path, std::shared_ptr<MachineStateFile>& state) {
  if (path.empty()) {
    return true;
  }
  auto file = MachineStateFile::open(path);
  if (!file) {
    std::cerr << "subfeed-sim: error: " << file.error().describe() << std::endl;
    return false;
  }
  state = std::make_shared<MachineStateFile>(std::move(*file));
  return true;
}

void add_state_options(CLI::App& cmd, std::string& log, std::string& machine_state) {
  cmd.add_option("--log", log, "Append every line to FILE once carried out (a move once ended)")
      ->type_name("FILE");
  cmd.add_option("--machine-state", machine_state,
                 "Keep the axes' position in FILE across controller restarts (absolute "
                 "encoders, or a machine homed again): read at start, written as it moves")
      ->type_name("FILE");
}

struct GrblCommand {
  GrblSimOptions sim;
  std::string tcp; // host:port; empty for a pty
  long error_on_line = 0, reset_on_line = 0, disconnect_on_line = 0, garbage_on_line = 0,
       lose_ack_on_line = 0, freeze_on_line = 0;
  double alarm_after_s = 0.0;
  long ack_delay_ms = 0;
  long boot_ms = 50;
  std::string machine_state;
  std::vector<double> work_offset;
};

void add_grbl_options(CLI::App& cmd, GrblCommand& c) {
  cmd.add_option("--axes", c.sim.axes, "Axes (3..6: XYZ, then A, B, C)")->check(CLI::Range(3, 6));
  cmd.add_option("--rx", c.sim.rx_buffer, "Serial RX buffer, bytes")->check(CLI::Range(16, 65536));
  cmd.add_option("--planner", c.sim.planner_blocks, "Planner blocks")->check(CLI::Range(2, 1024));
  cmd.add_option("--line-limit", c.sim.line_limit, "Longest line, characters")
      ->check(CLI::Range(16, 1024));
  cmd.add_option("--baud", c.sim.baud, "Emulated wire speed, baud (0 = unlimited)")
      ->check(CLI::Range(0, 4000000));
  cmd.add_flag("--grblhal", c.sim.grblhal, "Behave as grblHAL (banner, [OPT:], latching errors)");
  cmd.add_flag("--wpos", c.sim.report_wpos, "Report WPos instead of MPos");
  cmd.add_option("--speed", c.sim.motion.speed, "Run the machine N times faster than real time")
      ->check(positive_number());
  cmd.add_option("--accel", c.sim.motion.acceleration_mm_s2, "Acceleration, mm/s^2")
      ->check(positive_number());
  cmd.add_option("--rapid", c.sim.motion.rapid_mm_min, "Rapid rate, mm/min")
      ->check(positive_number());
  cmd.add_option("--tcp", c.tcp, "Serve on TCP HOST:PORT instead of a pty (port 0: any free)");
  add_state_options(cmd, c.sim.record.executed_log, c.machine_state);
  cmd.add_option("--work-offset", c.work_offset,
                 "G54 from the machine's zero, X,Y,Z[,A,B,C] (reported as WCO)")
      ->delimiter(',')
      ->expected(3, 6);
  cmd.add_option("--error-on-line", c.error_on_line, "Fault: answer program line K with an error")
      ->check(positive_number());
  cmd.add_option("--error-code", c.sim.faults.error_code, "Error code for --error-on-line")
      ->check(CLI::Range(1, 255));
  cmd.add_option("--alarm-after", c.alarm_after_s,
                 "Fault: ALARM this many seconds after the first program line")
      ->check(positive_number());
  cmd.add_option("--alarm-code", c.sim.faults.alarm_code, "Alarm code for --alarm-after")
      ->check(CLI::Range(1, 255));
  cmd.add_option("--reset-on-line", c.reset_on_line,
                 "Fault: the controller resets itself at program line K")
      ->check(positive_number());
  cmd.add_option("--disconnect-on-line", c.disconnect_on_line,
                 "Fault: the link drops at program line K")
      ->check(positive_number());
  cmd.add_option("--garbage-on-line", c.garbage_on_line,
                 "Fault: line noise before the reply to program line K")
      ->check(positive_number());
  cmd.add_option("--lose-ack-on-line", c.lose_ack_on_line,
                 "Fault: never acknowledge program line K")
      ->check(positive_number());
  cmd.add_option("--ack-delay", c.ack_delay_ms, "Fault: delay every reply by up to MS milliseconds")
      ->type_name("MS")
      ->check(CLI::Range(0L, 600000L));
  cmd.add_option("--seed", c.sim.faults.seed, "Random seed for delays");
  cmd.add_option("--boot-ms", c.boot_ms,
                 "Boot time after a connection (GRBL on Arduino resets on open)")
      ->check(CLI::Range(0L, 600000L));
}

std::optional<long> positive(long v) {
  return v > 0 ? std::optional<long>(v) : std::nullopt;
}

int serve_grbl(GrblCommand& c, const sigset_t& signals) {
  c.sim.faults.error_on_line = positive(c.error_on_line);
  c.sim.faults.reset_on_line = positive(c.reset_on_line);
  c.sim.faults.disconnect_on_line = positive(c.disconnect_on_line);
  c.sim.faults.garbage_on_line = positive(c.garbage_on_line);
  c.sim.faults.lose_ack_on_line = positive(c.lose_ack_on_line);
  c.sim.faults.freeze_on_line = positive(c.freeze_on_line);
  c.sim.faults.max_ack_delay = std::chrono::milliseconds(c.ack_delay_ms);
  c.sim.boot_time = std::chrono::milliseconds(c.boot_ms);
  if (c.alarm_after_s > 0.0) {
    c.sim.faults.alarm_after_s = c.alarm_after_s;
  }
  if (!open_machine_state(c.machine_state, c.sim.record.machine_state)) {
    return 2;
  }
  for (std::size_t i = 0; i < std::min<std::size_t>(6, c.work_offset.size()); ++i) {
    c.sim.work_offset[i] = c.work_offset[i];
  }
  std::unique_ptr<ByteChannel> channel;
  if (c.tcp.empty()) {
    auto pty = Pty::open();
    if (!pty) {
      std::cerr << "subfeed-sim: error: " << pty.error().describe() << std::endl;
      return 3;
    }
    channel = std::make_unique<Pty>(std::move(*pty));
  } else {
    const auto colon = c.tcp.rfind(':');
    const auto port = colon == std::string::npos
                          ? std::nullopt
                          : subfeed::parse_int(std::string_view(c.tcp).substr(colon + 1));
    if (colon == 0 || !port || *port < 0 || *port > 65535) {
      std::cerr << "subfeed-sim: usage: --tcp: expected HOST:PORT with a port 0..65535, got '"
                << c.tcp << "'" << std::endl;
      return 1;
    }
    auto listener = TcpListener::open(c.tcp.substr(0, colon), *port);
    if (!listener) {
      std::cerr << "subfeed-sim: error: " << listener.error().describe() << std::endl;
      return subfeed::exit_code(listener.error().code);
    }
    channel = std::make_unique<TcpListener>(std::move(*listener));
  }
  GrblSim sim(std::move(channel), c.sim);
  sim.start();
  std::cout << sim.address() << std::endl;
  int signal = 0;
  sigwait(&signals, &signal);
  sim.stop();
  const auto stats = sim.stats();
  std::cerr << "subfeed-sim: " << stats.executed_count << " lines executed, " << stats.refused_count
            << " refused, " << stats.dropped_count + stats.waiting_count << " dropped unread, "
            << stats.overrun_bytes << " bytes overrun, " << stats.eeprom_violations
            << " EEPROM violations, " << stats.alarms_sent << " alarms, " << stats.resets
            << " resets, " << stats.feed_holds << " feed holds, " << stats.overrides
            << " overrides, " << stats.starvations << " planner starvations, state " << stats.state
            << std::endl;
  return 0;
}

struct FanucCommand {
  FanucSimOptions sim;
  std::string machine_state;
  std::string framing = "7E2";
  long stuck_xoff_at = 0, lose_xon_after = 0, drop_at = 0;
  long max_pause_ms = 0;
  long link_latency_ms = 0;
};

void add_fanuc_options(CLI::App& cmd, FanucCommand& c) {
  cmd.add_option("--buffer", c.sim.buffer, "Receive buffer, bytes")->check(CLI::Range(16, 1 << 20));
  cmd.add_option("--high", c.sim.high_water, "Send DC3 (XOFF) at this fill")
      ->check(CLI::Range(1, 1 << 20));
  cmd.add_option("--low", c.sim.low_water, "Send DC1 (XON) again at this fill")
      ->check(CLI::Range(0, 1 << 20));
  cmd.add_option("--baud", c.sim.baud, "Emulated wire speed, baud (0 = unlimited)")
      ->check(CLI::Range(0, 4000000));
  cmd.add_option("--framing", c.framing, "Data bits, parity, stop bits, e.g. 7E2 or 8N1");
  cmd.add_option("--overrun-tolerance", c.sim.overrun_tolerance,
                 "Characters after DC3 before alarm 087")
      ->check(CLI::Range(0, 100000));
  cmd.add_option("--link-latency", c.link_latency_ms,
                 "Characters written within MS after DC3 are in flight, not an overrun")
      ->type_name("MS")
      ->check(CLI::Range(0, 60000));
  cmd.add_flag("--request-tape", c.sim.request_tape,
               "Ask for the tape (DC1) when a sender connects");
  cmd.add_flag("--eia", c.sim.eia_cr, "Blocks end with CR (EIA option) instead of LF");
  cmd.add_option("--speed", c.sim.motion.speed, "Run the machine N times faster than real time")
      ->check(positive_number());
  cmd.add_option("--stuck-xoff-at", c.stuck_xoff_at, "Fault: DC3 at block K and never DC1 again")
      ->check(positive_number());
  cmd.add_option("--lose-xon-after", c.lose_xon_after,
                 "Fault: the DC1 owed after block K is never sent")
      ->check(positive_number());
  cmd.add_option("--drop-at", c.drop_at, "Fault: the link drops at block K")
      ->check(positive_number());
  cmd.add_option("--max-pause", c.max_pause_ms,
                 "Drain jitter: random stalls of up to MS milliseconds")
      ->type_name("MS")
      ->check(CLI::Range(0L, 600000L));
  cmd.add_option("--seed", c.sim.seed, "Random seed for stalls");
  add_state_options(cmd, c.sim.record.executed_log, c.machine_state);
}

int serve_fanuc(FanucCommand& c, const sigset_t& signals) {
  if (c.framing.size() != 3 || (c.framing[0] != '7' && c.framing[0] != '8') ||
      std::string("NEO").find(c.framing[1]) == std::string::npos ||
      (c.framing[2] != '1' && c.framing[2] != '2')) {
    std::cerr << "subfeed-sim: usage: --framing: expected e.g. 7E2 or 8N1, got '" << c.framing
              << "'" << std::endl;
    return 1;
  }
  if (c.sim.low_water >= c.sim.high_water || c.sim.high_water > c.sim.buffer) {
    std::cerr << "subfeed-sim: usage: need --low < --high <= --buffer" << std::endl;
    return 1;
  }
  c.sim.data_bits = c.framing[0] - '0';
  c.sim.parity = c.framing[1];
  c.sim.stop_bits = c.framing[2] - '0';
  c.sim.faults.stuck_xoff_at_block = positive(c.stuck_xoff_at);
  c.sim.faults.lose_xon_after_block = positive(c.lose_xon_after);
  c.sim.faults.drop_at_block = positive(c.drop_at);
  c.sim.max_block_pause = std::chrono::milliseconds(c.max_pause_ms);
  c.sim.link_latency = std::chrono::milliseconds(c.link_latency_ms);
  c.sim.pause_one_in = 20;
  if (!open_machine_state(c.machine_state, c.sim.record.machine_state)) {
    return 2;
  }
  auto pty = Pty::open();
  if (!pty) {
    std::cerr << "subfeed-sim: error: " << pty.error().describe() << std::endl;
    return 3;
  }
  FanucSim control(std::make_unique<Pty>(std::move(*pty)), c.sim);
  control.start();
  std::cout << control.address() << std::endl;
  int signal = 0;
  sigwait(&signals, &signal);
  control.stop();
  const auto stats = control.stats();
  std::cerr << "subfeed-sim: " << stats.executed_count << " blocks executed, program "
            << (stats.program_number.empty() ? "-" : stats.program_number) << ", "
            << stats.xoff_sent << " XOFF, " << stats.xon_sent << " XON, at most "
            << stats.max_after_xoff << " characters after XOFF, alarm "
            << (stats.alarm.empty() ? "none" : stats.alarm) << std::endl;
  return 0;
}

} // namespace

int main(int argc, char** argv) {
  // Blocked before any thread starts, so only sigwait below sees them.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);

  CLI::App app{"subfeed-sim: a simulated machine controller on a pseudo-terminal", "subfeed-sim"};
  app.set_version_flag("--version", std::string("subfeed-sim ") + SUBFEED_VERSION);
  app.require_subcommand(1);
  GrblCommand grbl;
  CLI::App* grbl_cmd = app.add_subcommand("grbl", "A GRBL 1.1 / grblHAL controller");
  add_grbl_options(*grbl_cmd, grbl);
  FanucCommand fanuc;
  CLI::App* fanuc_cmd =
      app.add_subcommand("fanuc", "A Fanuc-style control reading a program by DNC");
  add_fanuc_options(*fanuc_cmd, fanuc);
  // An unknown command would otherwise read "A subcommand is required".
  if (argc > 1 && argv[1][0] != '-') {
    const auto commands = app.get_subcommands([](CLI::App*) { return true; });
    if (std::ranges::none_of(commands, [&](CLI::App* c) { return c->get_name() == argv[1]; })) {
      std::cerr << "subfeed-sim: usage: unknown command '" << argv[1]
                << "' (see subfeed-sim --help)" << std::endl;
      return 1;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) {
      return app.exit(e);
    }
    std::cerr << "subfeed-sim: usage: " << e.what() << " (see subfeed-sim --help)" << std::endl;
    return 1;
  }
  if (grbl_cmd->parsed()) {
    return serve_grbl(grbl, signals);
  }
  if (fanuc_cmd->parsed()) {
    return serve_fanuc(fanuc, signals);
  }
  return 1;
}
