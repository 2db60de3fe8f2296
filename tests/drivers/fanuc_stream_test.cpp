// The real DNC sender over a real pty against the simulated Fanuc-style control.

#include "drivers/fanuc_program.hpp"
#include "drivers/fanuc_streamer.hpp"
#include "drivers/live_program.hpp"
#include "sim/fanuc_sim.hpp"
#include "sim/pty.hpp"
#include "support/catch_printers.hpp"
#include "support/grbl_fixture.hpp"
#include "support/slow_program_writer.hpp"
#include "support/temp_dir.hpp"

#include <catch2/catch.hpp>
#include <thread>

using namespace std::chrono_literals;
using subfeed::ErrorCode;
using subfeed::drivers::FanucStreamOptions;
using subfeed::drivers::SerialOptions;
using subfeed::drivers::SerialParity;
using subfeed::sim::FanucSimOptions;

namespace {

struct FanucBench {
  explicit FanucBench(FanucSimOptions o,
                      SerialOptions framing = {9600, 7, SerialParity::even, 2,
                                               subfeed::drivers::SerialFlow::xon_xoff}) {
    o.record_executed = true;
    sim = std::make_unique<subfeed::sim::FanucSim>(
        std::make_unique<subfeed::sim::Pty>(subfeed::sim::Pty::open().value()), o);
    sim->start();
    options.serial = framing;
    port = std::make_unique<subfeed::drivers::SerialPort>(
        subfeed::drivers::SerialPort::open(sim->address(),
                                           subfeed::drivers::dnc_port_options(framing))
            .value());
  }

  subfeed::Expected<subfeed::drivers::StreamSummary>
  send(const std::string& program, subfeed::drivers::ControlInbox* inbox = nullptr) {
    auto file = subfeed::drivers::FanucProgram::open(dir.write("prog.nc", program)).value();
    const auto result = subfeed::drivers::stream_fanuc(*port, file, options, inbox, observer);
    std::this_thread::sleep_for(300ms); // let the control read what is on the wire
    return result;
  }

  subfeed::testing::TempDir dir;
  std::unique_ptr<subfeed::sim::FanucSim> sim;
  std::unique_ptr<subfeed::drivers::SerialPort> port;
  FanucStreamOptions options;
  subfeed::testing::RecordingObserver observer;
};

FanucSimOptions fast_control() {
  FanucSimOptions o;
  o.motion.speed = 1000.0;
  return o;
}

// Short feed moves: `count` blocks, each a few millimetres at 600 mm/min.
std::string moves(int count) {
  std::string p = "G21 G90 G17\nG01 F600\n";
  for (int i = 1; i <= count; ++i) {
    p += "X" + std::to_string(i % 2 * 3) + ".0 Y" + std::to_string(i % 3) + ".5\n";
  }
  return p;
}

std::vector<std::string> blocks_of(const std::string& program) {
  std::vector<std::string> blocks;
  std::istringstream in(program);
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty()) {
      blocks.push_back(line);
    }
  }
  return blocks;
}

} // namespace

TEST_CASE("DNC: a program arrives framed, exactly once, in order", "[pty]") {
  FanucBench bench(fast_control());
  bench.options.program_number = 1234;
  bench.options.xoff_timeout = 2000ms;
  const std::string program = moves(40);
  const auto summary = bench.send(program);
  const auto stats = bench.sim->stats();
  INFO("control: alarm '" << stats.alarm << "', xoff " << stats.xoff_sent << ", fill "
                          << stats.max_fill << ", blocks " << stats.blocks_received);
  REQUIRE(summary);
  CHECK(stats.alarm.empty());
  CHECK(stats.program_started);
  CHECK(stats.program_ended);
  CHECK(stats.program_number == "1234");
  CHECK(stats.executed == blocks_of(program));
}

TEST_CASE("DNC: a framed file is sent as it is", "[pty]") {
  FanucBench bench(fast_control());
  const std::string body = "G21 G90\nG01 X1.0 F300 (FIRST)\nX2.0\n";
  const auto summary = bench.send("%\nO0042 (PART)\n" + body + "%\n");
  REQUIRE(summary);
  CHECK(bench.sim->stats().program_number == "0042 (PART)");
  CHECK(bench.sim->stats().executed == blocks_of(body));
}

TEST_CASE("DNC: on XOFF the sender stops within one character", "[pty]") {
  auto o = fast_control();
  o.motion.speed = 20.0; // slow enough that the buffer fills again and again
  o.look_ahead_blocks = 2;
  o.buffer = 64;
  o.high_water = 40;
  o.low_water = 16;
  FanucBench bench(o);
  const std::string program = moves(80);
  REQUIRE(bench.send(program));
  const auto stats = bench.sim->stats();
  CHECK(stats.xoff_sent >= 3);
  CHECK(stats.max_after_xoff <= 1);
  CHECK(stats.alarm.empty());
  CHECK(stats.executed == blocks_of(program));
}

TEST_CASE("DNC: characters outside ISO 840 stop the job before anything is sent", "[pty]") {
  FanucBench bench(fast_control());
  const auto result = bench.send("G21 G90\nG01 x1.0 F300\n");
  REQUIRE_FALSE(result);
  CHECK(result.error().code == ErrorCode::bad_input);
  CHECK(result.error().where.line == 2);
  CHECK(result.error().message ==
        "'x' is not an ISO 840 tape character (the control would raise a TH alarm)");
  CHECK_FALSE(bench.sim->stats().program_started);
}

TEST_CASE("DNC: the sender can wait for the control to request the tape", "[pty]") {
  SECTION("requested") {
    auto o = fast_control();
    o.request_tape = true;
    FanucBench bench(o);
    bench.options.wait_for_request = true;
    bench.options.request_timeout = 2000ms;
    const std::string program = moves(10);
    REQUIRE(bench.send(program));
    CHECK(bench.sim->stats().executed == blocks_of(program));
  }
  SECTION("never requested") {
    FanucBench bench(fast_control());
    bench.options.wait_for_request = true;
    bench.options.request_timeout = 300ms;
    const auto result = bench.send(moves(10));
    REQUIRE_FALSE(result);
    CHECK(result.error().message == "the control did not request the tape (DC1) within 300 ms");
    CHECK_FALSE(bench.sim->stats().program_started);
  }
}

TEST_CASE("DNC: a restart from block N restores the modal state first", "[pty]") {
  FanucBench bench(fast_control());
  const std::string program = "G21 G17 G90 G94 G54\nT2 M06\nG43 H2 Z50.0\nS12000 M03\nM08\n"
                              "G00 X0 Y0\nG01 Z-1.0 F800\nX10.0\nX20.0 Y5.0\nX30.0\n";
  bench.options.from_line = 9;
  REQUIRE(bench.send(program));
  CHECK(bench.sim->stats().executed == std::vector<std::string>{"G21 G17 G90 G94 G54", "T2 M06",
                                                                "G43 H2", "S12000 M03", "M08",
                                                                "G01 F800", "X20.0 Y5.0", "X30.0"});
}

TEST_CASE("DNC: a resume's approach goes between the restored modes and the restart block",
          "[pty]") {
  FanucBench bench(fast_control());
  const std::string program = "G21 G90\nG00 X0 Y0\nG01 Z-1.0 F800\nX10.0\nX20.0\n";
  bench.options.from_line = 4;
  bench.options.restart_blocks = {"G94", "G00 Z50.0", "G01 X0 Y0 Z-1.0 F300", "G01 F800"};
  REQUIRE(bench.send(program));
  CHECK(bench.sim->stats().executed == std::vector<std::string>{"G21 G90", "G01 F800", "G94",
                                                                "G00 Z50.0", "G01 X0 Y0 Z-1.0 F300",
                                                                "G01 F800", "X10.0", "X20.0"});
}

TEST_CASE("DNC: a resume block outside ISO 840 is refused before anything is sent", "[pty]") {
  FanucBench bench(fast_control());
  bench.options.from_line = 2;
  bench.options.restart_blocks = {"G00 z50.0"};
  const auto refused = bench.send("G21 G90\nG00 X0 Y0\n");
  REQUIRE_FALSE(refused);
  CHECK(refused.error().where.key == "resume");
  CHECK(bench.sim->stats().blocks_received == 0);
  CHECK_FALSE(bench.sim->stats().program_started);
}

TEST_CASE("DNC: no restart inside cutter compensation", "[pty]") {
  FanucBench bench(fast_control());
  bench.options.from_line = 3;
  const auto result = bench.send("G21 G90\nG41 D1 G01 X0 Y0 F300\nX10.0\n");
  REQUIRE_FALSE(result);
  CHECK(
      result.error().message.starts_with("cannot restart inside cutter radius compensation (G41)"));
  CHECK(bench.sim->stats().executed.empty());
}

TEST_CASE("DNC: an XOFF that never ends is reported with the last block sent", "[pty]") {
  SECTION("stuck") {
    auto o = fast_control();
    o.faults.stuck_xoff_at_block = 5;
    FanucBench bench(o);
    bench.options.xoff_timeout = 300ms;
    const auto result = bench.send(moves(40));
    REQUIRE_FALSE(result);
    CHECK(result.error().code == ErrorCode::machine_fault);
    CHECK(result.error().message.starts_with(
        "the control has held the tape (XOFF) for 300 ms; last block sent: line "));
  }
  SECTION("lost XON") {
    auto o = fast_control();
    o.motion.speed = 20.0;
    o.look_ahead_blocks = 2;
    o.buffer = 64;
    o.high_water = 40;
    o.low_water = 16;
    o.faults.lose_xon_after_block = 3;
    FanucBench bench(o);
    bench.options.xoff_timeout = 300ms;
    const auto result = bench.send(moves(60));
    REQUIRE_FALSE(result);
    CHECK(result.error().message.starts_with("the control has held the tape (XOFF)"));
  }
}

TEST_CASE("DNC: a dropped port is reported with the last block sent", "[pty]") {
  auto o = fast_control();
  o.faults.drop_at_block = 10;
  FanucBench bench(o);
  const auto result = bench.send(moves(60));
  REQUIRE_FALSE(result);
  CHECK(result.error().code == ErrorCode::machine_fault);
  CHECK(result.error().message.find("last block sent: line ") != std::string::npos);
}

TEST_CASE("DNC: a stop-bit mismatch raises a TH alarm on the control", "[pty]") {
  // 7E1 against the control's 7E2 (a pty carries the stop bits, not data bits or parity).
  FanucBench bench(fast_control(), SerialOptions{9600, 7, SerialParity::even, 1,
                                                 subfeed::drivers::SerialFlow::xon_xoff});
  bench.options.xoff_timeout = 300ms;
  const auto result = bench.send(moves(10));
  REQUIRE_FALSE(result);
  CHECK(result.error().message.starts_with("the control has held the tape (XOFF)"));
  CHECK(bench.sim->stats().alarm == "TH framing: sender 1 stop bit(s), control 2");
}

TEST_CASE("DNC: a stop command stops sending at once", "[pty]") {
  auto o = fast_control();
  o.motion.speed = 5.0;
  FanucBench bench(o);
  auto inbox = subfeed::drivers::ControlInbox::create().value();
  std::jthread stopper([&inbox] {
    std::this_thread::sleep_for(300ms);
    inbox->push({subfeed::drivers::ControlCommand::Kind::stop, 0});
  });
  const auto result = bench.send(moves(200), inbox.get());
  REQUIRE_FALSE(result);
  CHECK(result.error().code == ErrorCode::stopped);
  CHECK(bench.sim->stats().blocks_received < 100);
}

TEST_CASE("DNC soak: 100,000 blocks with random drain, no overrun, exact delivery", "[pty][slow]") {
  auto o = fast_control();
  o.baud = 0;
  // At 460800 baud the sender writes 20 characters at a time and 46 a millisecond: the
  // room past the DC3 (high water 700, random pauses up to 40 ms make many XOFF cycles)
  // covers ~30 ms of either side not being scheduled on a loaded machine. This soak is
  // about exact delivery; the one-character XOFF figure is tested at 9600 baud. A pty
  // carries each direction through a kernel worker: on a loaded machine a DC3 has reached
  // the sender 32 ms late (1,500 characters), so the link's latency is taken as 250 ms.
  o.link_latency = 250ms;
  o.buffer = 4096;
  o.high_water = 700;
  o.low_water = 200;
  o.overrun_tolerance = 1500;
  o.max_block_pause = 40ms;
  o.pause_one_in = 500;
  o.motion.speed = 1e6;
  o.data_bits = 8;
  o.parity = 'N';
  o.stop_bits = 1;
  FanucBench bench(
      o, SerialOptions{460800, 8, SerialParity::none, 1, subfeed::drivers::SerialFlow::xon_xoff});
  std::string program;
  for (int i = 0; i < 100'000; ++i) {
    program += "X" + std::to_string(i % 97) + "." + std::to_string(i % 10) + " Y" +
               std::to_string(i % 89) + "\n";
  }
  const auto summary = bench.send(program);
  const auto stats = bench.sim->stats();
  INFO("control alarm: " << stats.alarm);
  REQUIRE(summary);
  CHECK(stats.alarm.empty());
  CHECK(stats.xoff_sent > 10);
  CHECK(stats.executed == blocks_of(program));
}

TEST_CASE("DNC: a port that accepts nothing (CTS held low) is reported", "[pty]") {
  // To the sender a dropped CTS is a port that takes no more bytes; a pty whose far side
  // stops reading does the same once its buffer is full.
  auto pty = subfeed::sim::Pty::open().value();
  const SerialOptions fast{460800, 8, SerialParity::none, 1, subfeed::drivers::SerialFlow::rts_cts};
  auto port =
      subfeed::drivers::SerialPort::open(pty.slave_path(), subfeed::drivers::dnc_port_options(fast))
          .value();
  subfeed::testing::TempDir dir;
  std::string program;
  for (int i = 0; i < 20000; ++i) {
    program += "X" + std::to_string(i % 100) + ".5 Y1.0\n";
  }
  auto file = subfeed::drivers::FanucProgram::open(dir.write("p.nc", program)).value();
  FanucStreamOptions options;
  options.serial = fast;
  subfeed::testing::RecordingObserver observer;
  const auto result = subfeed::drivers::stream_fanuc(port, file, options, nullptr, observer);
  REQUIRE_FALSE(result);
  CHECK(result.error().code == ErrorCode::machine_fault);
  CHECK(result.error().message.starts_with(
      "the port took nothing for 2000 ms (hardware handshake: CTS held low?)"));
  CHECK(result.error().message.find("last block sent: line ") != std::string::npos);
}

TEST_CASE("DNC: a stop while the program's writer pauses ends at once", "[pty]") {
  // Paused mid-program, and before its first block (which comes after the whole plan's
  // preparation).
  for (const std::size_t pause_after : {std::size_t{4}, std::size_t{0}}) {
    CAPTURE(pause_after);
    FanucBench bench(fast_control());
    subfeed::drivers::ProgramQueue queue(4);
    subfeed::drivers::LiveBlocks program("live.nc", queue);
    auto writer = subfeed::testing::write_slowly(queue, blocks_of(moves(6)), pause_after, 20s);
    auto inbox = subfeed::drivers::ControlInbox::create().value();
    std::jthread stopper([&inbox] {
      std::this_thread::sleep_for(800ms);
      inbox->push({subfeed::drivers::ControlCommand::Kind::stop, 0});
    });
    const auto start = std::chrono::steady_clock::now();
    const auto result = subfeed::drivers::stream_fanuc(*bench.port, program, bench.options,
                                                       inbox.get(), bench.observer);
    queue.close();
    REQUIRE_FALSE(result);
    CHECK(result.error().code == ErrorCode::stopped);
    CHECK(std::chrono::steady_clock::now() - start < 3s);
    if (pause_after == 0) {
      CHECK(bench.sim->stats().blocks_received == 0);
    }
  }
}

TEST_CASE("DNC: a tape request heard while the program is still coming is kept", "[pty]") {
  // The operator starts the control's tape read while subfeed waits for the plan's first
  // block: that DC1 is the request, not lost to a wait for another one.
  auto o = fast_control();
  o.request_tape = true; // DC1 as the sender connects, before any block is there
  FanucBench bench(o);
  bench.options.wait_for_request = true;
  bench.options.request_timeout = 2000ms;
  subfeed::drivers::ProgramQueue queue(4);
  subfeed::drivers::LiveBlocks program("live.nc", queue);
  const auto blocks = blocks_of(moves(6));
  auto writer = subfeed::testing::write_slowly(queue, blocks, 0, 2500ms); // past the timeout
  const auto result =
      subfeed::drivers::stream_fanuc(*bench.port, program, bench.options, nullptr, bench.observer);
  REQUIRE(result);
  std::this_thread::sleep_for(300ms);
  CHECK(bench.sim->stats().executed == blocks);
}
