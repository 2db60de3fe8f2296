// The real sender over a real pty against the simulated GRBL: every behaviour and fault.

#include "drivers/gcode_source.hpp"
#include "drivers/live_program.hpp"
#include "drivers/tcp_transport.hpp"
#include "sim/pty.hpp"
#include "sim/tcp_listener.hpp"
#include "support/catch_printers.hpp"
#include "support/grbl_fixture.hpp"
#include "support/slow_program_writer.hpp"

#include <catch2/catch.hpp>
#include <thread>

using namespace std::chrono_literals;
using subfeed::ErrorCode;
using subfeed::drivers::ControlCommand;
using subfeed::drivers::ControlInbox;
using subfeed::sim::GrblSimOptions;
using subfeed::testing::GrblBench;
using subfeed::testing::random_program;
using subfeed::testing::stripped_lines;

namespace {

GrblSimOptions fast_sim() {
  GrblSimOptions o;
  o.baud = 0;
  o.motion.speed = 1000.0;
  return o;
}

// A program whose moves take real time at speed 1: 20 mm at 600 mm/min each.
std::string slow_program(int moves) {
  std::string p = "G21G90\nG1F600\n";
  for (int i = 1; i <= moves; ++i) {
    p += "G1X" + std::to_string(i % 2 == 0 ? 0 : 20) + "Y" + std::to_string(i) + "\n";
  }
  return p;
}

// The n-th non-blank line of `program` (1-based) is on which file line?
long file_line_of(const std::string& program, long n) {
  long line = 0, seen = 0;
  std::size_t at = 0;
  while (at < program.size()) {
    const auto end = program.find('\n', at);
    ++line;
    if (!stripped_lines(program.substr(at, end - at)).empty() && ++seen == n) {
      return line;
    }
    at = end + 1;
  }
  return -1;
}

} // namespace

TEST_CASE("a program arrives exactly once, in order, without overrunning the RX buffer", "[pty]") {
  GrblBench bench(fast_sim());
  const std::string program = "(job)\ng21 g90\nG1 F1000 ; feed\n" + random_program(500, 79, 7);
  const auto summary = bench.stream(program);
  REQUIRE(summary);
  const auto stats = bench.sim->stats();
  CHECK(stats.executed == stripped_lines(program));
  CHECK(stats.overrun_bytes == 0);
  CHECK(stats.max_rx_fill <= 128);
  CHECK(stats.max_rx_fill > 64); // character counting keeps the buffer busy
  CHECK(summary->lines == static_cast<long>(stripped_lines(program).size()));
  CHECK(summary->controller.rx_buffer == 128);
  CHECK(summary->controller.rx_buffer_reported);
  CHECK(summary->controller.version == "1.1h.20190825");
  CHECK(bench.observer.last.lines_acked == bench.observer.last.lines_total);
  CHECK(stats.state == "Idle"); // the job ends when the machine is idle
}

TEST_CASE("the RX buffer size comes from $I, an override, or 128", "[pty]") {
  SECTION("reported") {
    auto o = fast_sim();
    o.rx_buffer = 256;
    GrblBench bench(o);
    REQUIRE(bench.stream(random_program(300, 79, 1)));
    CHECK(bench.observer.info.rx_buffer == 256);
    CHECK(bench.sim->stats().max_rx_fill > 128);
    CHECK(bench.sim->stats().overrun_bytes == 0);
  }
  SECTION("overridden") {
    auto o = fast_sim();
    o.rx_buffer = 256;
    GrblBench bench(o);
    auto options = GrblBench::fast_options();
    options.rx_buffer = 90;
    REQUIRE(bench.stream(random_program(300, 79, 2), options));
    CHECK(bench.sim->stats().max_rx_fill <= 90);
    CHECK_FALSE(bench.observer.info.rx_buffer_reported);
  }
  SECTION("absent") {
    auto o = fast_sim();
    o.report_build_options = false;
    GrblBench bench(o);
    REQUIRE(bench.stream(random_program(100, 79, 3)));
    CHECK(bench.observer.info.rx_buffer == 128);
    CHECK_FALSE(bench.observer.info.rx_buffer_reported);
  }
}

TEST_CASE("grblHAL: no banner on connect, 256-character lines, its own buffer", "[pty]") {
  auto o = fast_sim();
  o.grblhal = true;
  o.rx_buffer = 1024;
  o.line_limit = 256;
  GrblBench bench(o);
  const std::string program = random_program(300, 200, 4);
  REQUIRE(bench.stream(program));
  CHECK(bench.observer.info.grblhal);
  CHECK(bench.observer.info.line_limit == 256);
  CHECK(bench.observer.info.rx_buffer == 1024);
  CHECK(bench.sim->stats().executed == stripped_lines(program));
}

TEST_CASE("EEPROM writes go alone: no bytes arrive while the controller writes", "[pty]") {
  GrblBench bench(fast_sim());
  std::string program = random_program(100, 79, 5);
  program += "$10=2\nG10 L20 P1 X0 Y0\nG28.1\n" + random_program(100, 79, 6);
  REQUIRE(bench.stream(program));
  const auto stats = bench.sim->stats();
  CHECK(stats.eeprom_violations == 0);
  CHECK(stats.overrun_bytes == 0);
}

TEST_CASE("the simulator notices EEPROM writes with bytes waiting", "[pty]") {
  // The control for the test above: stream naively and the violation is seen.
  GrblBench bench(fast_sim());
  std::this_thread::sleep_for(50ms);
  const std::string burst = "$10=2\nG1X1F100\nG1X2\n";
  REQUIRE(bench.port->write(burst, 100ms).value() == burst.size());
  std::this_thread::sleep_for(200ms);
  CHECK(bench.sim->stats().eeprom_violations == 1);
}

TEST_CASE("with --send-and-wait one line is in flight", "[pty]") {
  GrblBench bench(fast_sim());
  auto options = GrblBench::fast_options();
  options.send_and_wait = true;
  const std::string program = random_program(100, 40, 8);
  REQUIRE(bench.stream(program, options));
  CHECK(bench.sim->stats().max_rx_fill <= 41);
  CHECK(bench.sim->stats().executed == stripped_lines(program));
}

TEST_CASE("a line over the limit stops the job before anything is sent", "[pty]") {
  GrblBench bench(fast_sim());
  const std::string program = "G1X1F100\nG1X" + std::string(77, '1') + "\nG1X2\n";
  const auto result = bench.stream(program);
  REQUIRE_FALSE(result);
  CHECK(result.error().code == ErrorCode::bad_input);
  CHECK(result.error().where.line == 2);
  CHECK(result.error().message ==
        "line is 80 characters after stripping; the controller takes at most 79");
  CHECK(bench.sim->stats().program_lines == 0);
}

TEST_CASE("error:N mid-stream holds, stops and resets the machine, and names the line", "[pty]") {
  auto o = fast_sim();
  o.faults.error_on_line = 50;
  GrblBench bench(o);
  const std::string program = random_program(300, 79, 9);
  const auto result = bench.stream(program);
  REQUIRE_FALSE(result);
  CHECK(result.error().code == ErrorCode::machine_fault);
  CHECK(result.error().where.line == file_line_of(program, 50));
  CHECK(result.error().message.starts_with(
      "controller error:20 (unsupported or invalid G-code command found in block)"));
  const auto stats = bench.sim->stats();
  // Lines after the error were taken and run, or dropped by the reset: only those are told.
  const bool dropped = stats.dropped_count + stats.waiting_count + stats.refused_count > 1;
  CHECK((result.error().message.find("sent but not run") != std::string::npos) == dropped);
  CHECK(stats.feed_holds >= 1);
  CHECK(stats.resets == 1);
  CHECK(stats.alarms_sent == 0); // held to a stop before the reset: no ALARM:3
  // Exactly once, in order: a prefix of the program without the rejected line.
  auto expected = stripped_lines(program);
  expected.erase(expected.begin() + 49);
  REQUIRE(stats.executed.size() >= 49);
  CHECK(std::equal(stats.executed.begin(), stats.executed.end(), expected.begin()));
}

TEST_CASE("with --continue-on-error each error is reported and the job finishes", "[pty]") {
  auto o = fast_sim();
  o.faults.error_on_line = 10;
  GrblBench bench(o);
  auto options = GrblBench::fast_options();
  options.continue_on_error = true;
  const std::string program = random_program(100, 79, 10);
  const auto summary = bench.stream(program, options);
  REQUIRE(summary);
  CHECK(summary->errors == 1);
  REQUIRE(bench.observer.errors.size() == 1);
  CHECK(bench.observer.errors[0].line == file_line_of(program, 10));
  CHECK(bench.observer.errors[0].code == 20);
  CHECK(bench.sim->stats().executed.size() == stripped_lines(program).size() - 1);
}

TEST_CASE("grblHAL's latched errors are told apart and the latch is cleared", "[pty]") {
  auto o = fast_sim();
  o.grblhal = true;
  o.line_limit = 256;
  o.faults.error_on_line = 10;
  GrblBench bench(o);
  auto options = GrblBench::fast_options();
  options.continue_on_error = true;
  const std::string program = random_program(200, 79, 11);
  const auto summary = bench.stream(program, options);
  REQUIRE(summary);
  REQUIRE_FALSE(bench.observer.errors.empty());
  CHECK_FALSE(bench.observer.errors[0].latched);
  for (std::size_t i = 1; i < bench.observer.errors.size(); ++i) {
    CHECK(bench.observer.errors[i].latched);
  }
  const auto executed = bench.sim->stats().executed;
  CHECK(executed.size() == stripped_lines(program).size() - bench.observer.errors.size());
  CHECK(executed.back() == stripped_lines(program).back()); // streaming went on after the latch
}

TEST_CASE("an ALARM stops streaming at once", "[pty]") {
  auto o = fast_sim();
  o.motion.speed = 1.0;
  o.faults.alarm_after_s = 0.3;
  GrblBench bench(o);
  const auto result = bench.stream(slow_program(200));
  REQUIRE_FALSE(result);
  CHECK(result.error().code == ErrorCode::machine_fault);
  CHECK(result.error().message.starts_with("controller ALARM:1 (hard limit triggered"));
  CHECK(result.error().message.find("last line acknowledged") != std::string::npos);
  CHECK(bench.sim->stats().program_lines < 40);
}

TEST_CASE("a controller that resets itself mid-job stops the stream", "[pty]") {
  auto o = fast_sim();
  o.faults.reset_on_line = 30;
  GrblBench bench(o);
  const auto result = bench.stream(random_program(200, 79, 12));
  REQUIRE_FALSE(result);
  CHECK(result.error().message.starts_with("the controller reset itself"));
  CHECK(bench.sim->stats().program_lines < 40);
}

TEST_CASE("a port that vanishes mid-job is reported with the last acknowledged line", "[pty]") {
  auto o = fast_sim();
  o.faults.disconnect_on_line = 30;
  GrblBench bench(o);
  const auto result = bench.stream(random_program(200, 79, 13));
  REQUIRE_FALSE(result);
  CHECK(result.error().code == ErrorCode::machine_fault);
  CHECK(result.error().message.starts_with("port vanished"));
  CHECK(result.error().message.find("last line acknowledged: ") != std::string::npos);
}

TEST_CASE("line noise from the controller is never counted", "[pty]") {
  auto o = fast_sim();
  o.faults.garbage_on_line = 20;
  GrblBench bench(o);
  const std::string program = random_program(100, 79, 14);
  const auto summary = bench.stream(program);
  REQUIRE(summary);
  CHECK(summary->unknown_replies >= 1);
  CHECK(bench.sim->stats().executed == stripped_lines(program));
}

TEST_CASE("a lost acknowledgement is detected and named", "[pty]") {
  auto o = fast_sim();
  o.faults.lose_ack_on_line = 20;
  GrblBench bench(o);
  const std::string program = random_program(100, 79, 15);
  const auto result = bench.stream(program);
  REQUIRE_FALSE(result);
  CHECK(result.error().message.starts_with(
      "acknowledgement lost: the controller is idle but 1 line(s) are unanswered"));
  // The lost answer leaves the count one line high, so streaming stalls and is stopped.
  const auto executed = bench.sim->stats().executed;
  const auto expected = stripped_lines(program);
  REQUIRE(executed.size() >= 20);
  CHECK(std::equal(executed.begin(), executed.end(), expected.begin()));
  CHECK(result.error().where.line == file_line_of(program, static_cast<long>(executed.size())));
}

TEST_CASE("slow, jittery acknowledgements still deliver exactly once", "[pty]") {
  auto o = fast_sim();
  o.faults.max_ack_delay = 15ms;
  GrblBench bench(o);
  const std::string program = random_program(150, 79, 16);
  REQUIRE(bench.stream(program));
  CHECK(bench.sim->stats().executed == stripped_lines(program));
  CHECK(bench.sim->stats().overrun_bytes == 0);
}

TEST_CASE("a stop command holds, waits for Hold:0 and resets without ALARM:3", "[pty]") {
  auto o = fast_sim();
  o.motion.speed = 1.0;
  GrblBench bench(o);
  auto inbox = ControlInbox::create().value();
  std::jthread stopper([&inbox] {
    std::this_thread::sleep_for(400ms);
    inbox->push({ControlCommand::Kind::stop, 0});
  });
  const auto result = bench.stream(slow_program(100), GrblBench::fast_options(), inbox.get());
  REQUIRE_FALSE(result);
  CHECK(result.error().code == ErrorCode::stopped);
  CHECK(result.error().message.starts_with("stopped by the user"));
  const auto stats = bench.sim->stats();
  CHECK(stats.feed_holds == 1);
  CHECK(stats.resets == 1);
  CHECK(stats.alarms_sent == 0);
  CHECK(std::ranges::find(stats.status_states, "Hold:0") != stats.status_states.end());
}

TEST_CASE("realtime bytes reach the controller while the line queue is full", "[pty]") {
  auto o = fast_sim();
  o.motion.speed = 1.0;
  GrblBench bench(o);
  auto inbox = ControlInbox::create().value();
  std::jthread overrider([&inbox] {
    std::this_thread::sleep_for(300ms); // the RX buffer and planner are full by now
    inbox->push({ControlCommand::Kind::realtime, subfeed::drivers::grbl_realtime::feed_plus_10});
    std::this_thread::sleep_for(100ms);
    inbox->push({ControlCommand::Kind::stop, 0});
  });
  const auto result = bench.stream(slow_program(100), GrblBench::fast_options(), inbox.get());
  CHECK(result.error().code == ErrorCode::stopped);
  CHECK(bench.sim->stats().overrides == 1);
}

TEST_CASE("with --check the file runs through check mode, then for real", "[pty]") {
  SECTION("clean") {
    GrblBench bench(fast_sim());
    auto options = GrblBench::fast_options();
    options.check_first = true;
    const std::string program = random_program(120, 79, 17);
    const auto summary = bench.stream(program, options);
    const auto seen = bench.sim->stats();
    INFO("sim: program lines " << seen.program_lines << ", checked " << seen.checked_lines
                               << ", state " << seen.state << ", resets " << seen.resets
                               << ", rx fill " << seen.max_rx_fill);
    REQUIRE(summary);
    const auto stats = bench.sim->stats();
    CHECK(stats.checked_lines == static_cast<long>(stripped_lines(program).size()));
    CHECK(stats.executed == stripped_lines(program));
    CHECK(bench.observer.phases == std::vector<std::string>{"check", "stream", "finishing"});
  }
  SECTION("with an error nothing runs") {
    GrblBench bench(fast_sim());
    auto options = GrblBench::fast_options();
    options.check_first = true;
    const std::string program = random_program(50, 79, 18) + "G5 X1\n" + random_program(50, 79, 19);
    const auto result = bench.stream(program, options);
    REQUIRE_FALSE(result);
    CHECK(result.error().code == ErrorCode::bad_input);
    CHECK(result.error().where.line == 53);
    CHECK(result.error().message.starts_with("check mode found 1 line(s) in error"));
    CHECK(bench.sim->stats().executed.empty());
    CHECK_FALSE(bench.sim->stats().check_mode);
  }
}

TEST_CASE("a controller in alarm is not streamed to", "[pty]") {
  auto o = fast_sim();
  o.alarm_on_boot = true;
  GrblBench bench(o);
  const auto result = bench.stream(random_program(10, 79, 20));
  REQUIRE_FALSE(result);
  CHECK(result.error().message ==
        "the controller is in ALARM state: home it ($H) or unlock it ($X) first");
  CHECK(bench.sim->stats().program_lines == 0);
}

TEST_CASE("a port with no controller behind it times out with a clear message", "[pty]") {
  auto pty = subfeed::sim::Pty::open().value();
  auto port = subfeed::drivers::SerialPort::open(pty.slave_path(), {}).value();
  subfeed::testing::TempDir dir;
  auto source = subfeed::drivers::GcodeSource::open(dir.write("a.nc", "G1X1F100\n"), {}).value();
  auto options = GrblBench::fast_options();
  options.connect_timeout = 300ms;
  subfeed::testing::RecordingObserver observer;
  const auto result = subfeed::drivers::stream_grbl(port, source, options, nullptr, observer);
  REQUIRE_FALSE(result);
  CHECK(result.error().message == "no answer from a GRBL controller within 300 ms (is it powered, "
                                  "and are the port and baud rate right?)");
}

TEST_CASE("streaming over TCP to a grblHAL", "[pty]") {
  auto o = fast_sim();
  o.grblhal = true;
  o.line_limit = 256;
  o.record_executed = true;
  auto listener = subfeed::sim::TcpListener::open("127.0.0.1", 0).value();
  subfeed::sim::GrblSim sim(std::make_unique<subfeed::sim::TcpListener>(std::move(listener)), o);
  sim.start();
  auto link = subfeed::drivers::TcpTransport::connect(sim.address(), 1000ms);
  REQUIRE(link);
  subfeed::testing::TempDir dir;
  const std::string program = random_program(300, 120, 21);
  auto source = subfeed::drivers::GcodeSource::open(dir.write("a.nc", program), {}).value();
  subfeed::testing::RecordingObserver observer;
  const auto summary =
      subfeed::drivers::stream_grbl(*link, source, GrblBench::fast_options(), nullptr, observer);
  REQUIRE(summary);
  CHECK(sim.stats().executed == stripped_lines(program));
}

TEST_CASE("soak: 100,000 lines with random lengths, reply delays and polls", "[pty][slow]") {
  auto o = fast_sim();
  o.faults.max_ack_delay = 1ms;
  o.faults.seed = 12345;
  o.record_executed = true;
  GrblBench bench(o);
  auto options = GrblBench::fast_options();
  options.status_hz = 20.0;
  const std::string program = random_program(100'000, 79, 22);
  const auto summary = bench.stream(program, options);
  REQUIRE(summary);
  const auto stats = bench.sim->stats();
  CHECK(stats.overrun_bytes == 0);
  CHECK(stats.eeprom_violations == 0);
  CHECK(stats.executed == stripped_lines(program));
  CHECK(stats.status_queries > 10);
}

TEST_CASE("the simulator drops and counts bytes a naive sender pushes past its RX buffer",
          "[pty]") {
  auto o = fast_sim();
  o.motion.speed = 1.0; // the planner fills and stops taking lines
  GrblBench bench(o);
  std::this_thread::sleep_for(50ms);
  std::string flood;
  for (int i = 0; i < 60; ++i) {
    flood += "G1X" + std::to_string(i % 2 * 50) + "F600\n";
  }
  REQUIRE(bench.port->write(flood, 100ms).value() == flood.size());
  std::this_thread::sleep_for(300ms);
  CHECK(bench.sim->stats().overrun_bytes > 0);
}

TEST_CASE("the simulator answers an over-long line with error:11", "[pty]") {
  GrblBench bench(fast_sim());
  std::this_thread::sleep_for(50ms);
  const std::string line = "G1X" + std::string(80, '1') + "\n";
  REQUIRE(bench.port->write(line, 100ms).value() == line.size());
  std::string reply;
  char buffer[256];
  const auto deadline = std::chrono::steady_clock::now() + 1s;
  while (reply.find("error:11") == std::string::npos &&
         std::chrono::steady_clock::now() < deadline) {
    reply.append(buffer, bench.port->read(buffer, 50ms).value_or(0));
  }
  CHECK(reply.find("error:11\r\n") != std::string::npos);
}

TEST_CASE("system commands mid-program wait for idle and their output is never counted", "[pty]") {
  GrblBench bench(fast_sim());
  const std::string program =
      random_program(50, 79, 23) + "$$\n$G\n$#\n" + random_program(50, 79, 24);
  const auto summary = bench.stream(program);
  REQUIRE(summary);
  CHECK(std::ranges::count_if(bench.observer.messages,
                              [](const std::string& m) { return m.starts_with("$"); }) > 20);
  CHECK(bench.sim->stats().errors_sent == 0); // no error:8 for a $ command while running
  CHECK(bench.sim->stats().executed.size() == stripped_lines(program).size() - 3);
}

TEST_CASE("with --keep-comments lines go as written and the controller strips them", "[pty]") {
  GrblBench bench(fast_sim());
  auto options = GrblBench::fast_options();
  options.keep_comments = true;
  const std::string program = "G21 G90 (metric)\nG1 F1000 ; feed\ng1 x10 y5\n";
  REQUIRE(bench.stream(program, options));
  CHECK(bench.sim->stats().executed == std::vector<std::string>{"G21G90", "G1F1000", "G1X10Y5"});
  CHECK(bench.observer.last.bytes_sent == static_cast<long>(program.size()));
}

TEST_CASE("a stop while waiting for a silent controller ends at once", "[pty]") {
  auto pty = subfeed::sim::Pty::open().value();
  auto port = subfeed::drivers::SerialPort::open(pty.slave_path(), {}).value();
  subfeed::testing::TempDir dir;
  auto source = subfeed::drivers::GcodeSource::open(dir.write("a.nc", "G1X1F100\n"), {}).value();
  auto options = GrblBench::fast_options();
  options.connect_timeout = 10s;
  auto inbox = ControlInbox::create().value();
  inbox->push({ControlCommand::Kind::stop, 0});
  subfeed::testing::RecordingObserver observer;
  const auto start = std::chrono::steady_clock::now();
  const auto result = subfeed::drivers::stream_grbl(port, source, options, inbox.get(), observer);
  REQUIRE_FALSE(result);
  CHECK(result.error().code == ErrorCode::stopped);
  CHECK(std::chrono::steady_clock::now() - start < 2s);
}

TEST_CASE("an empty program connects, sends nothing and ends", "[pty]") {
  GrblBench bench(fast_sim());
  const auto summary = bench.stream("(nothing to do)\n\n");
  REQUIRE(summary);
  CHECK(summary->lines == 0);
  CHECK(bench.sim->stats().program_lines == 0);
}

TEST_CASE("a controller that hangs, even on its last line, is reported as silent", "[pty]") {
  auto o = fast_sim();
  o.faults.freeze_on_line = 52; // the last line of the program
  GrblBench bench(o);
  auto options = GrblBench::fast_options();
  options.silence_timeout = 500ms;
  const auto result = bench.stream(random_program(50, 79, 25), options);
  REQUIRE_FALSE(result);
  CHECK(result.error().code == ErrorCode::machine_fault);
  CHECK(result.error().message.starts_with("no answer from the controller for 500 ms"));
}

namespace {

std::vector<std::string> numbered_moves(int count) {
  std::vector<std::string> lines{"G21G90", "(a comment the sender drops)", ""};
  for (int i = 1; i <= count; ++i) {
    lines.push_back("G1X" + std::to_string(i) + "F1000");
  }
  return lines;
}

} // namespace

TEST_CASE("a program still being written: the controller is served while the writer pauses",
          "[pty]") {
  // The writer pauses three times as long as the controller may stay silent: the sender
  // keeps polling, so the pause is no silence, and every line arrives once, in order.
  GrblBench bench(fast_sim());
  const auto lines = numbered_moves(12);
  for (const std::size_t pause_after : {std::size_t{1}, std::size_t{3}, std::size_t{8}}) {
    CAPTURE(pause_after);
    auto options = GrblBench::fast_options();
    options.silence_timeout = 500ms;
    subfeed::drivers::ProgramQueue q(4);
    subfeed::drivers::LiveGcode source("live.nc", q);
    const auto polls_before = bench.sim->stats().status_queries;
    auto writer = subfeed::testing::write_slowly(q, lines, pause_after, 1500ms);
    const auto summary =
        subfeed::drivers::stream_grbl(*bench.port, source, options, nullptr, bench.observer);
    q.close();
    REQUIRE(summary);
    CHECK(summary->lines == 13);
    CHECK(bench.sim->stats().status_queries - polls_before >= 3); // polled through the pause
  }
  std::vector<std::string> expected;
  for (int pass = 0; pass < 3; ++pass) {
    for (const auto& l : stripped_lines("G21G90\n")) {
      expected.push_back(l);
    }
    for (int i = 1; i <= 12; ++i) {
      expected.push_back("G1X" + std::to_string(i) + "F1000");
    }
  }
  CHECK(bench.sim->stats().executed == expected);
}

TEST_CASE("a stop while the program's writer pauses ends at once", "[pty]") {
  GrblBench bench(fast_sim());
  subfeed::drivers::ProgramQueue queue(4);
  subfeed::drivers::LiveGcode source("live.nc", queue);
  auto writer = subfeed::testing::write_slowly(queue, numbered_moves(6), 5, 20s);
  auto inbox = ControlInbox::create().value();
  std::jthread stopper([&inbox] {
    std::this_thread::sleep_for(600ms);
    inbox->push({ControlCommand::Kind::stop, 0});
  });
  const auto start = std::chrono::steady_clock::now();
  const auto result = subfeed::drivers::stream_grbl(*bench.port, source, GrblBench::fast_options(),
                                                    inbox.get(), bench.observer);
  queue.close(); // the writer learns nobody listens and ends
  REQUIRE_FALSE(result);
  CHECK(result.error().code == ErrorCode::stopped);
  CHECK(std::chrono::steady_clock::now() - start < 3s);
  CHECK(bench.sim->stats().executed_count == 3); // G21G90 and the two moves before the pause
}
