// `subfeed run` and `subfeed resume` as a user runs them: the sample seat planned, posted and
// streamed over real ptys to the simulated controllers, interrupted, and resumed.

#include "drivers/gcode_line.hpp"
#include "support/hand_made_cl.hpp"
#include "support/output_lines.hpp"
#include "support/run_process.hpp"
#include "support/temp_dir.hpp"
#include "support/text_file.hpp"

#include <catch2/catch.hpp>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

using subfeed::testing::BackgroundProcess;
using subfeed::testing::has_line;
using subfeed::testing::has_line_matching;
using subfeed::testing::lines_of;
using subfeed::testing::literal;
using subfeed::testing::read_text;
using subfeed::testing::run_process;
using subfeed::testing::split_lines;
using namespace std::chrono_literals;

namespace {

const std::string bin = SUBFEED_BIN;
const std::string sim_bin = SUBFEED_SIM_BIN;
const std::string source_dir = SUBFEED_SOURCE_DIR;
const std::string seat = source_dir + "/examples/seat.obj";
const std::string grblhal = source_dir + "/configs/grblhal-xyzac-trt.toml";
const std::string fanuc = source_dir + "/configs/fanuc-xyzac-trt.toml";

// Waits until a growing file has stopped growing (the machine has run what it holds).
void wait_until_still(const std::string& path) {
  std::uintmax_t last = 0;
  for (int i = 0; i < 100; ++i) {
    std::this_thread::sleep_for(300ms);
    const auto size = std::filesystem::file_size(path);
    if (size == last) {
      return;
    }
    last = size;
  }
}

// The line where resume says where the program continues and why (GRBL).
std::string resume_line(const std::string& journal, const std::string& why) {
  return "resume " + literal(journal) + R"(: continue after line \d+ \()" + literal(why) +
         R"(\); last sent \d+, last acknowledged \d+)";
}

// The dry run's verdict: every block executed as posted, and the replay's line with no
// limit violation and no rotary jump ("controller" for GRBL, "control" for a Fanuc-style one).
void check_dry_run_verdict(const std::string& out, const std::string& controller) {
  CHECK(has_line_matching(out, "dry run: the simulated " + controller +
                                   R"( executed (\d+) of \1 posted blocks, exactly as posted )"
                                   R"(\(hash equal\))"));
  CHECK(has_line_matching(out, R"(  replayed through the xyzac-trt kinematics: tool tip within )"
                               R"([0-9.]+ mm of the CL path \(line \d+\) \(tolerance 0\.002 )"
                               R"(mm\), tool axis within [0-9.]+ deg \(line \d+\); limit )"
                               R"(violations 0, rotary jumps 0, blocks over an axis max feed 0)"));
}

std::vector<std::string> job(const std::string& base, const std::string& machine) {
  return {bin,      "run",       seat,   "--machine", machine, "--tool",
          "ball:6", "--scallop", "0.02", "-o",        base};
}

} // namespace

// Whole jobs on the seat run in the release build only (label parts), like the sample-part
// plans: under the sanitizers they take minutes. So do the resumes of whole seat jobs; the
// resume of a short sent program runs in both builds.
TEST_CASE("run --sim on the seat for a grblHAL A/C trunnion: executed as posted, on the CL path",
          "[slow][parts]") {
  subfeed::testing::TempDir dir;
  const std::string base = (dir.path() / "seat").string();
  // The tool by its name in the shipped table, with a lead: the journal keeps its sizes.
  std::vector<std::string> argv{
      bin,          "run",     seat,
      "--machine",  grblhal,   "--tool",
      "ball6-er32", "--tools", std::string(SUBFEED_SOURCE_DIR) + "/configs/tools.toml",
      "--lead",     "10",      "--scallop",
      "0.02",       "-o",      base};
  argv.insert(argv.end(), {"--sim", "--sim-speed", "50", "--sim-baud", "0"});
  const auto r = run_process(argv);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  check_dry_run_verdict(r.out, "controller");
  CHECK(has_line_matching(r.out, R"(  posted program: [0-9]+ poses \([0-9]+ in rapids\) as the )"
                                 R"(machine moves its joints checked against the part: .*; the )"
                                 R"(whole tool kept its clearance and stayed above the floor)"));
  CHECK(has_line_matching(r.out, R"(  first block reached the controller [0-9.]+ s after start, )"
                                 R"(the first move [0-9.]+ s after start)"));
  for (const char* ext : {".cl", ".nc", ".nc.map", ".journal"}) {
    CHECK(std::filesystem::exists(base + ext));
  }
  const auto journal = read_text(base + ".journal");
  CHECK(has_line_matching(journal, R"(\d+ event job cage=)" + literal(seat) +
                                       " .* tool=ball:6 .* flute=18 shank=6 stickout=40 "
                                       "holder=32:40 .* lead=10 tilt=0.*"));
  CHECK(has_line_matching(split_lines(journal).back(), R"(\d+ end done)"));
}

TEST_CASE("run --sim on the seat for a Fanuc-style A/C trunnion by DNC drip feed",
          "[slow][parts]") {
  subfeed::testing::TempDir dir;
  const std::string base = (dir.path() / "seat").string();
  auto argv = job(base, fanuc);
  argv.insert(argv.end(), {"--sim", "--sim-speed", "50", "--sim-baud", "0"});
  const auto r = run_process(argv);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  check_dry_run_verdict(r.out, "control");
}

namespace {

// The program's lines as the controller logs them (stripped, upper case).
std::vector<std::string> program_lines(const std::string& nc) {
  std::vector<std::string> program;
  for (const auto& line : lines_of(nc)) {
    program.push_back(subfeed::drivers::prepare_line(line, {256, false}, {}).value().text);
  }
  return program;
}

// Checks that `executed` holds every program line exactly once, in order, and otherwise
// only restart blocks (modes and the approach; `restart_block` tells them apart from the
// program's own), at most `restarts` of them.
void require_exactly_once(const std::vector<std::string>& program,
                          const std::vector<std::string>& executed, int restarts,
                          bool (*restart_block)(const std::string&)) {
  std::size_t next = 0;
  int restart_blocks = 0;
  for (const auto& line : executed) {
    if (next < program.size() && line == program[next]) {
      ++next;
    } else {
      INFO(line);
      CHECK(restart_block(line));
      ++restart_blocks;
    }
  }
  CHECK(next == program.size());
  CHECK(restart_blocks > 0);
  CHECK(restart_blocks <= restarts);
}

// GRBL programs have no N numbers: restart blocks are the G-word lines subfeed adds.
bool grbl_restart_block(const std::string& line) {
  return line.front() == 'G';
}

// Every block of a Fanuc-style run program has an N number; the restart blocks have none.
bool dnc_restart_block(const std::string& line) {
  return line.front() != 'N';
}

// Runs the seat job on `machine` against the controller `first`, kills the controller 8 s
// in, and checks that run failed as it should, with the program complete for a resume.
void kill_controller_mid_job(BackgroundProcess& first, const std::string& base,
                             const std::string& machine) {
  const std::string port = first.first_line();
  auto argv = job(base, machine);
  argv.insert(argv.end(), {"--port", port});
  BackgroundProcess sender(argv);
  std::this_thread::sleep_for(8s);
  first.signal(SIGKILL);
  const auto failed = sender.wait();
  CHECK(failed.exit_code == 3);
  CHECK(has_line_matching(failed.err, "subfeed: warning: the program is complete in " +
                                          literal(base + ".nc") + ": `subfeed resume " +
                                          literal(base + ".journal") + "` continues the job"));
  REQUIRE(std::filesystem::exists(base + ".nc"));
}

std::vector<std::string> sim_args(const std::string& log) {
  return {sim_bin, "grbl",      "--grblhal", "--axes",       "6",   "--rx",
          "1024",  "--planner", "100",       "--line-limit", "256", "--speed",
          "3",     "--baud",    "0",         "--log",        log};
}

} // namespace

TEST_CASE("subfeed killed mid-job: resume rebuilds the program and runs every line exactly once",
          "[slow][parts]") {
  subfeed::testing::TempDir dir;
  const std::string base = (dir.path() / "seat").string();
  const std::string log = (dir.path() / "executed.log").string();
  // The part's zero is away from the machine's: the controller reports MPos and, now and
  // then, WCO; the program's coordinates are the difference.
  auto args = sim_args(log);
  args.insert(args.end(), {"--work-offset", "10,-5,20,0,0,0"});
  BackgroundProcess sim(args);
  const std::string port = sim.first_line();
  REQUIRE(port.starts_with("/dev/pts/"));
  auto argv = job(base, grblhal);
  argv.insert(argv.end(), {"--port", port});
  BackgroundProcess sender(argv);
  std::this_thread::sleep_for(8s);
  sender.signal(SIGKILL);
  (void)sender.wait();
  // No waiting here: the controller may still be running what it holds when the resume
  // asks for its position, and the resume must wait for it to stop.
  REQUIRE_FALSE(std::filesystem::exists(base + ".nc")); // it died before the program was whole
  const auto resumed = run_process({bin, "resume", base + ".journal", "--port", port, "--yes"});
  INFO(resumed.out << resumed.err);
  REQUIRE(resumed.exit_code == 0);
  CHECK(has_line_matching(
      resumed.out, resume_line(base + ".journal", "the machine stands at the end of that line")));
  require_exactly_once(program_lines(base + ".nc"), lines_of(log), 16, grbl_restart_block);
}

TEST_CASE("a simulated controller killed mid-job: resume on a new one runs every block once",
          "[slow][parts]") {
  // The machine keeps its position (absolute encoders, or homed again): the new controller
  // reports where the old one stopped, mid-move, and the resume runs that move again from
  // its start. Without it the controller's position is lost and the resume starts early
  // enough that nothing is skipped.
  const bool keeps_position = GENERATE(true, false);
  CAPTURE(keeps_position);
  subfeed::testing::TempDir dir;
  const std::string base = (dir.path() / "seat").string();
  const std::string first_log = (dir.path() / "first.log").string();
  const std::string second_log = (dir.path() / "second.log").string();
  const std::string state = (dir.path() / "machine.state").string();
  const auto controller = [&](const std::string& log) {
    auto args = sim_args(log);
    if (keeps_position) {
      args.insert(args.end(), {"--machine-state", state});
    }
    return args;
  };
  BackgroundProcess first(controller(first_log));
  kill_controller_mid_job(first, base, grblhal);
  BackgroundProcess second(controller(second_log));
  const std::string port2 = second.first_line();
  const auto resumed = run_process({bin, "resume", base + ".journal", "--port", port2, "--yes"});
  INFO(resumed.out << resumed.err);
  REQUIRE(resumed.exit_code == 0);
  const auto program = program_lines(base + ".nc");
  const auto ran_first = lines_of(first_log);
  REQUIRE(ran_first.size() < program.size());
  auto ran = ran_first;
  const auto ran_second = lines_of(second_log);
  ran.insert(ran.end(), ran_second.begin(), ran_second.end());
  if (keeps_position) {
    // The machine kept its position: found on a move, not "on no move ... may be cut again".
    CHECK((has_line_matching(resumed.out,
                             resume_line(base + ".journal", "the machine stands at the end of that "
                                                            "line")) ||
           has_line_matching(resumed.out,
                             resume_line(base + ".journal", "the machine stopped inside the next "
                                                            "line's move: it runs again from its "
                                                            "start"))));
    require_exactly_once(program, ran, 16, grbl_restart_block);
    return;
  }
  // A fresh controller at zero usually matches no move and the resume says how many lines
  // may be cut again; when the job had not got far (a slow build) the program's first move
  // starts at zero, and the resume rightly starts there. Either way nothing is skipped:
  // the program's last lines ran on the second controller; where they start is where it
  // resumed, and that must be no later than where the first one stopped.
  std::size_t matched = 0;
  while (matched < ran_second.size() && matched < program.size() &&
         ran_second[ran_second.size() - 1 - matched] == program[program.size() - 1 - matched]) {
    ++matched;
  }
  CHECK(program.size() - matched <= ran_first.size());
}

// A whole seat job too (see above): under the sanitizers the planner has not always handed
// over a line by the time the stop comes, and the stop then names no line.
TEST_CASE("Ctrl-C during run stops the machine without an alarm and finishes the files",
          "[slow][parts]") {
  subfeed::testing::TempDir dir;
  const std::string base = (dir.path() / "seat").string();
  auto argv = job(base, grblhal);
  argv.insert(argv.end(), {"--sim", "--sim-speed", "2"});
  BackgroundProcess sender(argv);
  std::this_thread::sleep_for(7s);
  sender.signal(SIGINT);
  const auto r = sender.wait();
  CHECK(r.exit_code == 4);
  CHECK(
      has_line_matching(r.err, "subfeed: error: " + literal(base + ".nc") +
                                   R"(:\d+: stopped by the user; last line acknowledged: \d+.*)"));
  const auto journal = read_text(base + ".journal");
  CHECK_FALSE(has_line_matching(journal, R"(\d+ event alarm .*)"));
  CHECK(has_line_matching(journal, R"(\d+ event hold .*)"));
  CHECK(std::filesystem::exists(base + ".nc"));
}

TEST_CASE("run with a bad machine config names it and writes nothing", "[unit]") {
  subfeed::testing::TempDir dir;
  const std::string base = (dir.path() / "seat").string();
  const std::string machine = (dir.path() / "m.toml").string();
  std::ofstream(machine) << "[machine]\nname = \"x\"\nkinematics = \"warp-drive\"\n";
  auto argv = job(base, machine);
  argv.insert(argv.end(), {"--sim"});
  const auto r = run_process(argv);
  CHECK(r.exit_code == 2);
  CHECK(r.err == "subfeed: error: " + machine +
                     ":3: machine.kinematics: 'warp-drive' is not one of xyz, xyzac-trt, "
                     "xyzbc-trt, xyzac-head\n");
  for (const char* ext : {".cl", ".nc", ".nc.map", ".journal"}) {
    CHECK_FALSE(std::filesystem::exists(base + ext));
  }
}

TEST_CASE("resume refuses journals it cannot continue, in one line naming the journal", "[unit]") {
  subfeed::testing::TempDir dir;
  const std::string journal = (dir.path() / "job.journal").string();
  const auto resume = [&](const std::string& text) {
    std::ofstream(journal) << text;
    return run_process({bin, "resume", journal, "--port", "/dev/null", "--yes"});
  };
  SECTION("not a journal") {
    const auto r = resume("G1 X1\n");
    CHECK(r.exit_code == 2);
    CHECK(r.err == "subfeed: error: " + journal + ":1: not a subfeed journal (no start record)\n");
  }
  SECTION("a finished job") {
    const auto r = resume("0 start protocol=grbl program=a.nc link=/dev/pts/9\n"
                          "5 sent line=1 bytes=4\n7 answered line=1 ok\n9 end done\n");
    CHECK(r.exit_code == 2);
    CHECK(r.err == "subfeed: error: " + journal + ": the job finished: nothing to resume\n");
  }
  SECTION("a DNC job") {
    const auto r = resume("0 start protocol=fanuc program=a.nc link=/dev/pts/9\n"
                          "5 sent line=1 bytes=4\n");
    CHECK(r.exit_code == 1);
    CHECK(r.err == "subfeed: error: " + journal +
                       ": --block: a DNC control reports no position: give the sequence number "
                       "it shows for the block it stopped in (--block N) or the program line "
                       "(--from LINE)\n");
  }
  SECTION("a damaged job record") {
    const auto r = resume("0 start protocol=grbl program=a.nc link=/dev/pts/9\n"
                          "1 event job cage=seat.obj machine=m.toml output=seat tool=ball:6 "
                          "scallop=zero\n");
    CHECK(r.exit_code == 2);
    CHECK(r.err == "subfeed: error: " + journal + ": job: job record without a valid 'scallop'\n");
  }
}

TEST_CASE("run on existing CL data posts it as `post` does and streams it lazily", "[pty]") {
  subfeed::testing::TempDir dir;
  const std::string plane = source_dir + "/examples/plane.obj";
  const std::string cl = (dir.path() / "plane.cl").string();
  const auto planned = run_process(
      {bin, "plan", plane, "--tool", "ball:6", "--scallop", "0.05", "--axis", "fixed", "-o", cl});
  REQUIRE(planned.exit_code == 0);
  const std::string router = source_dir + "/configs/grbl-router-3axis.toml";
  const std::string base = (dir.path() / "job").string();
  const std::string before = read_text(cl);
  const auto r = run_process({bin, "run", cl, "--cage", plane, "--machine", router, "--sim",
                              "--sim-speed", "1000", "--sim-baud", "0", "-o", base, "--json"});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(has_line_matching(r.out, R"(\{"event":"job","passes":\d+,"cl_points":\d+,"lines":\d+,)"
                                 R"("cut_mm":[0-9.]+,"machine_min":[0-9.]+,"first_block_s":)"
                                 R"([0-9.]+,"first_move_s":[0-9.]+,"streamed_s":[0-9.]+\})"));
  CHECK(has_line_matching(r.out, R"(dry run: the simulated controller executed (\d+) of \1 posted )"
                                 R"(blocks, exactly as posted \(hash equal\))"));
  CHECK_FALSE(std::filesystem::exists(base + ".cl")); // the input is the job's CL data
  CHECK(read_text(cl) == before);
  const std::string posted = (dir.path() / "posted.nc").string();
  REQUIRE(run_process({bin, "post", cl, "--machine", router, "-o", posted}).exit_code == 0);
  CHECK(read_text(base + ".nc") == read_text(posted));
  CHECK(read_text(base + ".nc.map") == read_text(posted + ".map"));
  CHECK(has_line_matching(read_text(base + ".journal"),
                          R"(\d+ event job cage=)" + literal(cl) + " .*"));
}

TEST_CASE("run refuses CL data without its cage, and a rapid through the part before it is "
          "streamed",
          "[pty]") {
  subfeed::testing::TempDir dir;
  const std::string plane = source_dir + "/examples/plane.obj";
  const std::string router = source_dir + "/configs/grbl-router-3axis.toml";
  // Line 16's rapid dives through the plane z = 0.
  const auto cl = dir.write("through.cl", subfeed::testing::rapid_through_plane_cl);
  const std::string base = (dir.path() / "job").string();
  const auto unchecked =
      run_process({bin, "run", cl.string(), "--machine", router, "--sim", "-o", base});
  CHECK(unchecked.exit_code == 1);
  CHECK(unchecked.err == "subfeed: error: --cage: CL data reaches the machine only checked "
                         "against the part: give the cage it was made for\n");
  CHECK_FALSE(std::filesystem::exists(base + ".journal"));
  const auto r = run_process({bin, "run", cl.string(), "--cage", plane, "--machine", router,
                              "--sim", "--sim-speed", "1000", "--sim-baud", "0", "-o", base});
  CHECK(r.exit_code == 2);
  // The machine is held at once: the report says what it had acknowledged when it stopped.
  REQUIRE(split_lines(r.err).size() == 1);
  CHECK(has_line_matching(
      r.err, literal("subfeed: error: " + cl.string() +
                     ":16: tool path refused: the rapid from (10.0000, 0.0000, 2.0000) to "
                     "(-10.0000, 5.0000, -1.0000) touches the part (the ball 1.0000 mm deep) at "
                     "(-10.0000, 5.0000, 0.0000); last line acknowledged: ") +
                 R"(\d+(; \d+ line\(s\) sent but not run \(lines [0-9, -]+\))?)"));
  CHECK_FALSE(std::filesystem::exists(base + ".nc"));
  // Nothing of the refused rapid reached the controller: every block sent serves a CL line
  // before it (by the trace map of the same path posted up to it).
  const auto good = dir.write("good.cl", subfeed::testing::rapid_through_plane_sound_part_cl);
  const std::string good_nc = (dir.path() / "good.nc").string();
  REQUIRE(run_process({bin, "post", good.string(), "--machine", router, "-o", good_nc}).exit_code ==
          0);
  long last_before = 0;
  std::istringstream map(read_text(good_nc + ".map"));
  for (std::string row; std::getline(map, row);) {
    long nc_line = 0, cl_line = 0;
    if (std::sscanf(row.c_str(), "%ld %ld", &nc_line, &cl_line) == 2 && cl_line > 0) {
      last_before = nc_line;
    }
  }
  REQUIRE(last_before > 0);
  std::istringstream journal(read_text(base + ".journal"));
  for (std::string row; std::getline(journal, row);) {
    long sent = 0;
    if (std::sscanf(row.c_str(), "%*s sent line=%ld", &sent) == 1) {
      INFO(row);
      CHECK(sent <= last_before);
    }
  }
}

TEST_CASE("run refuses planning flags with CL data and needs them with a cage", "[unit]") {
  subfeed::testing::TempDir dir;
  const std::string base = (dir.path() / "job").string();
  SECTION("CL data with --tool") {
    const auto r = run_process({bin, "run", source_dir + "/examples/bowl-raster.cl", "--cage",
                                source_dir + "/examples/bowl.obj", "--machine", grblhal, "--tool",
                                "ball:6", "--sim", "-o", base});
    CHECK(r.exit_code == 1);
    CHECK(r.err == "subfeed: error: --tool: plans come from a cage: CL data already has its path "
                   "and cutter\n");
  }
  SECTION("a cage without --scallop") {
    const auto r = run_process(
        {bin, "run", seat, "--machine", grblhal, "--tool", "ball:6", "--sim", "-o", base});
    CHECK(r.exit_code == 1);
    CHECK(r.err == "subfeed: error: --scallop: planning from a cage needs --tool and --scallop\n");
  }
  for (const char* ext : {".cl", ".nc", ".nc.map", ".journal"}) {
    CHECK_FALSE(std::filesystem::exists(base + ext));
  }
}

TEST_CASE("a Fanuc-style control killed mid-job: resume by the block it shows runs every block "
          "once",
          "[slow][parts]") {
  // DNC reports no position: the operator reads the sequence number of the block the control
  // stopped in (here: the first block the dead control had not finished) and gives it. The
  // machine keeps its position (absolute encoders); on a trunnion the retract is straight up.
  subfeed::testing::TempDir dir;
  const std::string base = (dir.path() / "seat").string();
  const std::string machine = (dir.path() / "fanuc.toml").string();
  std::string config = read_text(fanuc);
  config.replace(config.find("baud = 9600"), 11, "baud = 115200");
  std::ofstream(machine) << config;
  const std::string first_log = (dir.path() / "first.log").string();
  const std::string second_log = (dir.path() / "second.log").string();
  const std::string state = (dir.path() / "machine.state").string();
  // 50 ms of link latency: this is about resuming, not the sender's DC3 reaction, and a
  // pty on a loaded machine can take longer than 10 characters at 115200 baud to hand the
  // DC3 over. The first control runs slowly enough that the lazy planner keeps its buffer
  // full even on a loaded machine: when it is killed it is inside a block it was sent.
  const auto control = [&](const std::string& log, const char* speed) {
    return std::vector<std::string>{sim_bin,           "fanuc", "--baud",         "0",
                                    "--speed",         speed,   "--log",          log,
                                    "--machine-state", state,   "--link-latency", "50"};
  };
  BackgroundProcess first(control(first_log, "3"));
  kill_controller_mid_job(first, base, machine);
  std::vector<std::string> program; // the blocks the control runs: all but '%' and O
  for (const auto& line : lines_of(base + ".nc")) {
    if (!line.empty() && line != "%" && line.front() != 'O') {
      program.push_back(line);
    }
  }
  const auto ran_first = lines_of(first_log);
  REQUIRE(!ran_first.empty());
  REQUIRE(ran_first.size() < program.size());
  REQUIRE(program[ran_first.size() - 1] == ran_first.back());
  const std::string shown = program[ran_first.size()]; // "N123 ..."
  REQUIRE(shown.front() == 'N');
  const std::string block = shown.substr(1, shown.find(' ') - 1);
  BackgroundProcess second(control(second_log, "10"));
  const std::string port2 = second.first_line();
  const auto resumed =
      run_process({bin, "resume", base + ".journal", "--port", port2, "--block", block, "--yes"});
  INFO(resumed.out << resumed.err);
  REQUIRE(resumed.exit_code == 0);
  // Inside a block when killed, or (a loaded machine whose planner fell behind) idle with
  // every block it was sent finished: either way the next block runs from its start.
  const auto dnc_line = [&](const std::string& why) {
    return "resume " + literal(base + ".journal") + R"(: continue after line \d+ \()" +
           literal(why) + R"(\); last sent \d+)";
  };
  const bool inside =
      has_line_matching(resumed.out, dnc_line("block N" + block + " runs again from its start"));
  const bool next = has_line_matching(
      resumed.out, dnc_line("block N" + block + ", the first not sent, runs from its start"));
  CHECK((inside || next));
  wait_until_still(second_log); // DNC has no acknowledgements: the control is still moving
  auto ran = ran_first;
  const auto ran_second = lines_of(second_log);
  ran.insert(ran.end(), ran_second.begin(), ran_second.end());
  require_exactly_once(program, ran, 24, dnc_restart_block);
}

TEST_CASE("resume after subfeed died with the planner full: a controller that goes on, and one "
          "that resets when the port opens",
          "[pty]") {
  // subfeed dies with the planner full of 0.125 s moves. grblHAL goes on running them while
  // the resume connects: looking at once would find the machine inside a move it is about
  // to finish, and run that move twice; the resume waits for it to stop. GRBL on an Arduino
  // resets when the port opens and drops its queue, the machine stopping mid-move: that move
  // runs again from its start.
  const bool grblhal = GENERATE(true, false);
  CAPTURE(grblhal);
  subfeed::testing::TempDir dir;
  std::string text = "G21 G90 G94\nG1 Z-1 F600\n";
  for (int i = 1; i <= 100; ++i) {
    text += "G1 X" + std::to_string(5 * i) + " Y" + std::to_string(i % 2) + "\n";
  }
  const std::string program = dir.write("moves.nc", text).string();
  const std::string log = (dir.path() / "executed.log").string();
  std::vector<std::string> args{sim_bin, "grbl", "--speed", "4", "--baud", "0", "--log", log};
  if (grblhal) {
    args.emplace_back("--grblhal");
  }
  BackgroundProcess sim(args);
  const std::string port = sim.first_line();
  BackgroundProcess sender({bin, "send", program, "--port", port});
  std::this_thread::sleep_for(1500ms);
  sender.signal(SIGKILL);
  (void)sender.wait();
  if (!grblhal) {
    // The simulator sees the port close by polling for the hang-up, which a loaded machine
    // can delay past a resume started at once (a real Arduino's reset on DTR cannot be
    // missed); a user restarting subfeed takes longer than this anyway.
    std::this_thread::sleep_for(300ms);
  }
  const auto resumed =
      run_process({bin, "resume", program + ".journal", "--port", port, "--machine",
                   source_dir + "/configs/grbl-router-3axis.toml", "--yes"});
  INFO(resumed.out << resumed.err);
  REQUIRE(resumed.exit_code == 0);
  if (grblhal) {
    CHECK(has_line(resumed.out, "the machine is still moving (Run): waiting for it to stop"));
    CHECK(
        has_line_matching(resumed.out, resume_line(program + ".journal",
                                                   "the machine stands at the end of that line")));
  } else {
    CHECK(has_line_matching(resumed.out,
                            resume_line(program + ".journal",
                                        "the machine stopped inside the next line's move: it "
                                        "runs again from its start")));
  }
  require_exactly_once(program_lines(program), lines_of(log), 16, grbl_restart_block);
}

TEST_CASE("a DNC resume refuses what the user gave wrong, in one line, before touching the port",
          "[unit]") {
  subfeed::testing::TempDir dir;
  const auto program =
      dir.write("job.nc", "%\nO1234\nN1 G21 G90\nN2 G0 X1.\nN3 G1 X2. F100.\nN4 X3.\n%\n").string();
  const std::string journal = (dir.path() / "job.journal").string();
  const std::string text = "0 start protocol=fanuc program=" + program +
                           " link=/dev/pts/9\n5 sent line=4 bytes=10\n"; // "N2 G0 X1." and its LF
  std::ofstream(journal) << text;
  const std::string head = source_dir + "/configs/grblhal-xyzac-head.toml";
  const auto resume = [&](const std::string& machine, std::vector<std::string> flags) {
    std::vector<std::string> argv{bin,         "resume", journal, "--port", "/nonexistent/tty",
                                  "--machine", machine,  "--yes"};
    argv.insert(argv.end(), flags.begin(), flags.end());
    return run_process(argv);
  };
  SECTION("--at with a word that is not a number") {
    const auto r = resume(fanuc, {"--block", "2", "--at", "1,2,x,4,5"});
    CHECK(r.exit_code == 1);
    CHECK(r.err == "subfeed: error: --at: 'x' is not a number\n");
  }
  SECTION("--at with too few positions") {
    const auto r = resume(fanuc, {"--block", "2", "--at", "1,2"});
    CHECK(r.exit_code == 1);
    CHECK(r.err == "subfeed: error: --at: expected 5 positions (one per axis of the machine), "
                   "got 2\n");
  }
  SECTION("a head that tilts the tool, without --at") {
    const auto r = resume(head, {"--block", "2"});
    CHECK(r.exit_code == 1);
    CHECK(r.err == "subfeed: error: --at: the tool tilts with the head: give the machine "
                   "position the control shows, so that the retract follows the tool's axis\n");
  }
  SECTION("a block past the first not sent: the blocks before it would be skipped") {
    const auto r = resume(fanuc, {"--block", "4"});
    CHECK(r.exit_code == 1);
    CHECK(r.err == "subfeed: error: " + program +
                       ": --block: no block N4 among the 4 lines sent or the next block\n");
  }
  SECTION("--tcp for drip feed") {
    const auto r = run_process({bin, "resume", journal, "--tcp", "localhost:1", "--machine", fanuc,
                                "--block", "2", "--yes"});
    CHECK(r.exit_code == 1);
    CHECK(r.err == "subfeed: error: --tcp: DNC drip feed runs over a serial port, not --tcp\n");
  }
  CHECK(read_text(journal) == text); // nothing appended
}

TEST_CASE("a machine state file that is not one is refused, named and left as it was", "[unit]") {
  subfeed::testing::TempDir dir;
  const auto state = dir.write("machine.state", "hello\n").string();
  const auto r = run_process({sim_bin, "grbl", "--machine-state", state});
  CHECK(r.exit_code == 2);
  CHECK(r.err ==
        "subfeed-sim: error: " + state + ":1: not a machine state record (six axis positions)\n");
  CHECK(read_text(state) == "hello\n");
}
