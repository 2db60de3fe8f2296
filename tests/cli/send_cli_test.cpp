// `subfeed send` and `subfeed-sim` as a user runs them, over real ptys.

#include "sim/pty.hpp"
#include "support/output_lines.hpp"
#include "support/run_process.hpp"
#include "support/temp_dir.hpp"
#include "support/text_file.hpp"

#include <catch2/catch.hpp>
#include <csignal>
#include <fstream>
#include <sstream>
#include <thread>

using subfeed::testing::BackgroundProcess;
using subfeed::testing::has_line;
using subfeed::testing::has_line_matching;
using subfeed::testing::literal;
using subfeed::testing::run_process;
using subfeed::testing::split_lines;
using namespace std::chrono_literals;

namespace {

const std::string bin = SUBFEED_BIN;
const std::string sim_bin = SUBFEED_SIM_BIN;
const std::string source_dir = SUBFEED_SOURCE_DIR;

std::string moves(int count, int feed) {
  std::string p = "G21 G90 (setup)\nG1 F" + std::to_string(feed) + "\n";
  for (int i = 1; i <= count; ++i) {
    p += "G1 X" + std::to_string(i % 2 * 10) + " Y" + std::to_string(i) + "\n";
  }
  return p;
}

// The simulated GRBL controller's account on SIGTERM, with the counts a test pins down.
std::string grbl_account(const std::string& alarms_resets_holds) {
  return R"(subfeed-sim: \d+ lines executed, \d+ refused, \d+ dropped unread, 0 bytes overrun, )"
         R"(0 EEPROM violations, )" +
         alarms_resets_holds + R"(, \d+ overrides, \d+ planner starvations, state Idle)";
}

// A journal line: milliseconds since the start, then the record.
std::string journal_line(const std::string& record_pattern) {
  return R"(\d+ )" + record_pattern;
}

} // namespace

TEST_CASE("send --sim streams a file and summarises", "[pty]") {
  const subfeed::testing::TempDir dir;
  const auto job = dir.write("job.nc", moves(200, 3000));
  const auto r = run_process({bin, "send", job.string(), "--sim", "grbl", "--sim-speed", "1000"});
  CHECK(r.err.empty());
  CHECK(r.exit_code == 0);
  REQUIRE(split_lines(r.out).size() == 1);
  CHECK(has_line_matching(r.out, R"(done: 202 lines, 1[0-9]{3} bytes in \d+\.\d\d s \(\d+ )"
                                 R"(bytes/s, link use \d+\.\d% of 115200 baud\))"));
}

TEST_CASE("send --json prints one event per line", "[pty]") {
  const subfeed::testing::TempDir dir;
  const auto job = dir.write("job.nc", moves(50, 3000));
  const auto r =
      run_process({bin, "send", job.string(), "--sim", "grblhal", "--sim-speed", "1000", "--json"});
  CHECK(r.exit_code == 0);
  const auto lines = split_lines(r.out);
  for (const auto& line : lines) {
    CHECK(has_line_matching(line, R"(\{"event":"[a-z_]+"(,"[a-z_]+":.*)?\})")); // one object
  }
  CHECK(has_line_matching(r.out, R"(\{"event":"connected","grblhal":true,.*\})"));
  CHECK(has_line(r.out, R"({"event":"phase","name":"stream"})"));
  REQUIRE_FALSE(lines.empty());
  CHECK(has_line_matching(lines.back(), R"(\{"event":"done","lines":52,"bytes":\d+,"seconds":)"
                                        R"([0-9.]+,"bytes_per_s":[0-9.]+,"errors":0\})"));
}

TEST_CASE("send with a machine config takes its settings, a contradicting simulator is refused",
          "[pty]") {
  const subfeed::testing::TempDir dir;
  const auto job = dir.write("job.nc", moves(20, 3000));
  const auto ok = run_process({bin, "send", job.string(), "--sim", "grbl", "--sim-speed", "1000",
                               "--machine", source_dir + "/configs/grbl-router-3axis.toml"});
  CHECK(ok.exit_code == 0);
  const auto fanuc = run_process({bin, "send", job.string(), "--sim", "grbl", "--machine",
                                  source_dir + "/configs/fanuc-xyzac-trt.toml"});
  CHECK(fanuc.exit_code == 1);
  CHECK(fanuc.err == "subfeed: error: --sim: --sim grbl speaks grbl, not the fanuc protocol\n");
}

TEST_CASE("send refuses bad command lines and bad files with the right exit code", "[pty]") {
  const subfeed::testing::TempDir dir;
  const auto job = dir.write("job.nc", moves(5, 3000));
  CHECK(run_process({bin, "send", job.string()}).exit_code == 1); // no link
  CHECK(
      run_process({bin, "send", job.string(), "--sim", "grbl", "--port", "/dev/null"}).exit_code ==
      1);
  CHECK(run_process({bin, "send", job.string(), "--sim", "bogus"}).exit_code == 1);
  CHECK(
      run_process({bin, "send", job.string(), "--sim", "fanuc", "--protocol", "grbl"}).exit_code ==
      1);
  const auto missing =
      run_process({bin, "send", (dir.path() / "nope.nc").string(), "--sim", "grbl"});
  CHECK(missing.exit_code == 2);
  CHECK(missing.err ==
        "subfeed: error: " + (dir.path() / "nope.nc").string() + ": cannot open G-code file\n");
  const auto bad = dir.write("bad.nc", "G1 X1 F100\nG1 X2 (why?)\n");
  const auto realtime = run_process({bin, "send", bad.string(), "--sim", "grbl"});
  CHECK(realtime.exit_code == 2);
  CHECK(realtime.err == "subfeed: error: " + bad.string() +
                            ":2: '?' would act as a realtime command on the controller\n");
  const auto no_port = run_process({bin, "send", job.string(), "--port", "/dev/nonexistent-tty"});
  CHECK(no_port.exit_code == 3);
  CHECK(has_line_matching(no_port.err,
                          R"(subfeed: error: /dev/nonexistent-tty: cannot open serial )"
                          R"(port: No such file or directory; serial ports here: .+)"));
  const auto ports = run_process({bin, "ports"});
  CHECK(ports.exit_code == 0);
  CHECK_FALSE(ports.out.empty());
}

TEST_CASE("subfeed-sim serves a pty that send --port streams to, an error:N exits 3", "[pty]") {
  const subfeed::testing::TempDir dir;
  const auto job = dir.write("job.nc", moves(100, 3000));
  BackgroundProcess sim({sim_bin, "grbl", "--speed", "1000", "--error-on-line", "40"});
  const std::string port = sim.first_line();
  REQUIRE(port.starts_with("/dev/pts/"));
  const auto r = run_process({bin, "send", job.string(), "--port", port});
  CHECK(r.exit_code == 3);
  const std::string failure =
      literal(job.string() + ":40: controller error:20 (unsupported or invalid G-code command "
                             "found in block); last line acknowledged: ") +
      R"(\d+(; \d+ line\(s\) sent but not run \(lines [0-9, -]+\))?)";
  REQUIRE(split_lines(r.err).size() == 1);
  CHECK(has_line_matching(r.err, "subfeed: error: " + failure));
  const std::string journal = subfeed::testing::read_text(job.string() + ".journal");
  CHECK(has_line_matching(journal, journal_line(literal("start protocol=grbl program=" +
                                                        job.string() + " link=" + port))));
  CHECK(has_line_matching(journal, journal_line("answered line=39 ok")));
  CHECK(has_line_matching(journal, journal_line("answered line=40 error:20")));
  CHECK(has_line_matching(journal, journal_line("event hold stopping the machine")));
  CHECK(has_line_matching(journal, journal_line("event reset soft reset after Hold:0")));
  CHECK(has_line_matching(split_lines(journal).back(), journal_line("end failed " + failure)));
  sim.signal(SIGTERM);
  const auto served = sim.wait();
  CHECK(served.exit_code == 0);
  CHECK(has_line_matching(served.err, grbl_account(R"(0 alarms, 1 resets, \d+ feed holds)")));
}

TEST_CASE("Ctrl-C stops the machine safely and exits 4", "[pty]") {
  const subfeed::testing::TempDir dir;
  const auto job = dir.write("job.nc", moves(100, 600)); // slow: 10 mm at 600 mm/min each
  BackgroundProcess sim({sim_bin, "grbl"});
  const std::string port = sim.first_line();
  BackgroundProcess sender({bin, "send", job.string(), "--port", port});
  std::this_thread::sleep_for(800ms);
  sender.signal(SIGINT);
  const auto sent = sender.wait();
  CHECK(sent.exit_code == 4);
  CHECK(has_line_matching(sent.err,
                          literal("subfeed: error: " + job.string() + ":") +
                              R"(\d+: stopped by the user; last line acknowledged: \d+)"
                              R"((; \d+ line\(s\) sent but not run \(lines [0-9, -]+\))?)"));
  sim.signal(SIGTERM);
  const auto served = sim.wait();
  CHECK(has_line_matching(served.err, grbl_account("0 alarms, 1 resets, 1 feed holds")));
}

TEST_CASE("subfeed-sim serves TCP for send --tcp", "[pty]") {
  const subfeed::testing::TempDir dir;
  const auto job = dir.write("job.nc", moves(50, 3000));
  BackgroundProcess sim({sim_bin, "grbl", "--grblhal", "--speed", "1000", "--tcp", "127.0.0.1:0"});
  const std::string address = sim.first_line();
  REQUIRE(address.starts_with("127.0.0.1:"));
  const auto r = run_process({bin, "send", job.string(), "--tcp", address});
  CHECK(r.exit_code == 0);
  CHECK(has_line_matching(r.out, R"(done: 52 lines, \d+ bytes in \d+\.\d\d s \(\d+ bytes/s\))"));
}

TEST_CASE("a reader that closes the JSON pipe early does not kill the job", "[pty]") {
  const subfeed::testing::TempDir dir;
  const auto job = dir.write("job.nc", moves(300, 3000));
  const std::string command = bin + " send " + job.string() +
                              " --sim grbl --sim-speed 1000 --json | head -c 1 > /dev/null; "
                              "exit ${PIPESTATUS[0]}";
  const auto r = run_process({"/bin/bash", "-c", command});
  CHECK(r.exit_code == 0);
}

TEST_CASE("keys on the terminal reach the controller as realtime commands", "[pty]") {
  const subfeed::testing::TempDir dir;
  const auto job = dir.write("job.nc", moves(100, 600)); // slow enough to type into
  BackgroundProcess sim({sim_bin, "grbl"});
  const std::string port = sim.first_line();
  auto terminal = subfeed::sim::Pty::open().value(); // the user's terminal
  BackgroundProcess sender({bin, "send", job.string(), "--port", port}, terminal.slave_path());
  std::this_thread::sleep_for(700ms);
  REQUIRE(terminal.write_all(std::string_view("++-")));
  std::this_thread::sleep_for(200ms);
  REQUIRE(terminal.write_all(std::string_view("q")));
  const auto sent = sender.wait();
  CHECK(sent.exit_code == 4);
  sim.signal(SIGTERM);
  const auto served = sim.wait();
  INFO("sender: " << sent.err << " / sim: " << served.err);
  CHECK(has_line_matching(served.err,
                          R"(subfeed-sim: \d+ lines executed, \d+ refused, \d+ dropped unread, )"
                          R"(0 bytes overrun, 0 EEPROM violations, 0 alarms, 1 resets, 1 feed )"
                          R"(holds, 3 overrides, \d+ planner starvations, state Idle)"));
}

TEST_CASE("send --sim fanuc drip-feeds a program", "[pty]") {
  const subfeed::testing::TempDir dir;
  const auto job = dir.write("job.nc", "G21 G90 G17\nG01 F600\nX1.0 Y2.0\nX3.0\n");
  const auto r = run_process({bin, "send", job.string(), "--sim", "fanuc", "--sim-speed", "100"});
  CHECK(r.exit_code == 0);
  CHECK(has_line_matching(r.out, R"(done: 7 lines, 46 bytes in \d+\.\d\d s \(\d+ bytes/s, )"
                                 R"(link use \d+\.\d% of 9600 baud\))"));
  const auto bad = dir.write("bad.nc", "G21\nG01 X1.0 F600, (COMMA)\n");
  const auto refused = run_process({bin, "send", bad.string(), "--sim", "fanuc"});
  CHECK(refused.exit_code == 2);
  CHECK(refused.err ==
        "subfeed: error: " + bad.string() +
            ":2: ',' is not an ISO 840 tape character (the control would raise a TH alarm)\n");
}

TEST_CASE("send --protocol fanuc takes the machine's framing and O-number", "[pty]") {
  const subfeed::testing::TempDir dir;
  const auto job = dir.write("job.nc", "G21 G90\nG01 X1.0 F600\nX2.0\n");
  BackgroundProcess control({sim_bin, "fanuc", "--speed", "100"});
  const std::string port = control.first_line();
  const auto r = run_process({bin, "send", job.string(), "--port", port, "--machine",
                              source_dir + "/configs/fanuc-xyzac-trt.toml"});
  CHECK(r.exit_code == 0);
  std::this_thread::sleep_for(200ms);
  control.signal(SIGTERM);
  const auto served = control.wait();
  CHECK(has_line_matching(served.err, R"(subfeed-sim: 3 blocks executed, program 1234, \d+ XOFF, )"
                                      R"(\d+ XON, at most \d+ characters after XOFF, alarm none)"));
}

TEST_CASE("a control that holds the tape too long ends the job with exit 3", "[pty]") {
  const subfeed::testing::TempDir dir;
  std::string program = "G21 G90\nG01 F600\n";
  for (int i = 0; i < 300; ++i) { // more than the control's 256-byte buffer
    program += "X" + std::to_string(i % 5) + ".0\n";
  }
  const auto job = dir.write("job.nc", program);
  BackgroundProcess control({sim_bin, "fanuc", "--stuck-xoff-at", "10"});
  const std::string port = control.first_line();
  const auto r = run_process(
      {bin, "send", job.string(), "--protocol", "fanuc", "--port", port, "--xoff-timeout", "0.5"});
  CHECK(r.exit_code == 3);
  const std::string failure = literal(job.string()) + R"(:(\d+): the control has held the tape )"
                                                      R"(\(XOFF\) for 500 ms; last block sent: )"
                                                      R"(line \1)";
  CHECK(has_line_matching(r.err, "subfeed: error: " + failure));
  const std::string journal = subfeed::testing::read_text(job.string() + ".journal");
  CHECK(has_line_matching(journal, journal_line(literal("start protocol=fanuc program=" +
                                                        job.string() + " link=" + port))));
  CHECK(has_line_matching(journal, journal_line("event xoff")));
  CHECK(has_line_matching(split_lines(journal).back(), journal_line("end failed " + failure)));
}

TEST_CASE("subfeed-sim fanuc refuses a negative link latency in one line", "[unit]") {
  const auto r = run_process({sim_bin, "fanuc", "--link-latency", "-5"});
  CHECK(r.exit_code == 1);
  CHECK(r.out.empty()); // no pty offered
  CHECK(r.err == "subfeed-sim: usage: --link-latency: Value -5 not in range 0 to 60000 (see "
                 "subfeed-sim --help)\n");
}

TEST_CASE("a journal that cannot be written stops the job before it starts", "[pty]") {
  const subfeed::testing::TempDir dir;
  const auto job = dir.write("job.nc", moves(5, 3000));
  const auto r = run_process(
      {bin, "send", job.string(), "--sim", "grbl", "--journal", "/nonexistent/dir/j.journal"});
  CHECK(r.exit_code == 2);
  CHECK(r.err == "subfeed: error: /nonexistent/dir/j.journal: --journal: cannot open journal: No "
                 "such file or directory\n");
}
