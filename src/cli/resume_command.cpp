// `subfeed resume JOURNAL (--port DEV | --tcp HOST:PORT)`: continues a job after a lost link,
// an alarm, a dead controller or a crash of subfeed itself.
//
// Where to continue. GRBL: the controller is asked where the machine stands, and that
// position is looked up among the program's moves between the last acknowledged line less a
// planner's reach and the last line sent (restart_point.hpp): at the end of a move the
// program continues after it; inside one (the controller died mid-move, its machine keeping
// its position) that move runs again from its start, so every block runs once. A position on
// no move (the controller lost it) restarts early enough that nothing is skipped, and says
// how many lines may be cut twice. DNC: the control reports nothing, so the user gives the
// sequence number it shows (--block N), and the position it shows when the tool is tilted
// on a head (--at). --from LINE overrides either.
//
// Before the program continues, the modes are restored and the tool comes back safely
// (restart_approach.hpp). All of it is shown first and sent only after a yes (or --yes).

#include "base/number_text.hpp"
#include "command.hpp"
#include "control_thread.hpp"
#include "controller_link.hpp"
#include "job_pipeline.hpp"
#include "option_checks.hpp"
#include "restart_approach.hpp"
#include "restart_point.hpp"
#include "run_job.hpp"
#include "stream_reporter.hpp"

#include "drivers/fanuc_program.hpp"
#include "drivers/fanuc_streamer.hpp"
#include "drivers/gcode_source.hpp"
#include "drivers/grbl_reply.hpp"
#include "drivers/grbl_streamer.hpp"
#include "drivers/journal.hpp"
#include "drivers/journal_reader.hpp"
#include "drivers/live_program.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <iostream>
#include <sstream>
#include <unistd.h>
#include <utility>

namespace subfeed::cli {

namespace {

constexpr long planner_reach = 128; // lines a GRBL-style planner (and its RX buffer) can hold

struct ResumeOptions {
  std::string journal;
  std::string port, tcp;
  std::string machine;
  long from = 0;
  long block = -1; // DNC: the sequence number the control shows
  std::string at;  // DNC: the machine position the control shows, "X,Y,Z,..."
  bool yes = false;
  double clearance = 0.0; // mm; 0: the job's clearance, else the machine's retract
  double plunge_feed = 0.0;
  double connect_timeout_s = 5.0;
};

// What the journal and the job say: the program, where it stopped, the machine.
struct Interrupted {
  drivers::JournalSummary journal;
  std::optional<RunOptions> job;
  post::MachineConfig machine;
  bool dnc = false;
};

// Where the program continues and how the machine gets there.
struct Restart {
  long after = 0;
  std::string why;
  std::vector<std::string> blocks; // the modes, the approach, the modes again
};

// What the controller says once connected and idle: state and machine position.
class StatusProbe final : public drivers::StreamObserver {
public:
  void progress(const drivers::StreamProgress& p) override {
    if (p.status) {
      status = p.status;
    }
  }
  std::optional<drivers::StatusReport> status;
};

Expected<drivers::StatusReport> probe(drivers::Transport& link, const ResumeOptions& o) {
  drivers::ProgramQueue nothing(1);
  nothing.close();
  drivers::LiveGcode empty("(status)", nothing);
  drivers::GrblStreamOptions options;
  options.connect_timeout = std::chrono::milliseconds(static_cast<long>(o.connect_timeout_s * 1e3));
  StatusProbe observer;
  SUBFEED_TRY(drivers::stream_grbl(link, empty, options, nullptr, observer));
  if (!observer.status || observer.status->machine_position.size() < 3) {
    return fail(ErrorCode::machine_fault, "the controller reported no position", {});
  }
  return *observer.status;
}

bool moving(const drivers::StatusReport& status) {
  return status.state == "Run" || status.state == "Jog" || status.state == "Home" ||
         (status.state == "Hold" && status.substate != 0);
}

// Asks for a status report ('?', a realtime byte) and returns the newest that came back
// within 200 ms (5 a second, as GRBL wants at most); other lines are dropped.
Expected<std::optional<drivers::StatusReport>> poll_status(drivers::Transport& link,
                                                           std::string& pending) {
  SUBFEED_TRY(
      drivers::write_all(link, std::span<const char>("?", 1), std::chrono::milliseconds(1000)));
  char buffer[512];
  SUBFEED_TRY_ASSIGN(const auto got,
                     link.read(std::span<char>(buffer), std::chrono::milliseconds(200)));
  pending.append(buffer, got);
  std::optional<drivers::StatusReport> newest;
  for (auto end = pending.find('\n'); end != std::string::npos; end = pending.find('\n')) {
    auto line = std::string_view(pending).substr(0, end);
    if (line.ends_with('\r')) {
      line.remove_suffix(1);
    }
    if (auto report = drivers::parse_status(line)) {
      newest = std::move(report);
    }
    pending.erase(0, end + 1);
  }
  return newest;
}

// A controller that lost only its link runs what it holds, and a hold decelerates: where
// the machine stands is known once it stands still.
Expected<void> wait_until_still(drivers::Transport& link, const ResumeOptions& o, Logger& log) {
  constexpr auto wait_for_motion = std::chrono::minutes(10);
  const auto start = std::chrono::steady_clock::now();
  const auto silent = std::chrono::milliseconds(static_cast<long>(o.connect_timeout_s * 1e3));
  std::string pending;
  bool told = false;
  while (true) {
    SUBFEED_TRY_ASSIGN(const auto report, poll_status(link, pending));
    const auto waited = std::chrono::steady_clock::now() - start;
    if (report && !moving(*report)) {
      return {};
    }
    if (report && !std::exchange(told, true)) {
      log.info("the machine is still moving (" + report->state + "): waiting for it to stop");
    }
    if (!told && waited > silent) {
      return {}; // no report: the handshake says why
    }
    if (waited > wait_for_motion) {
      return fail(ErrorCode::machine_fault, "the machine did not stop within 10 minutes", {});
    }
  }
}

// Status reports until one says where the work offset is (GRBL adds WCO to one report in 10
// to 30); after `polls` without, the report stays as it is.
Expected<drivers::StatusReport> with_work_offset(drivers::Transport& link,
                                                 drivers::StatusReport status, int polls) {
  std::string pending;
  for (int i = 0; i < polls && !status.work_position && !status.work_offset; ++i) {
    SUBFEED_TRY_ASSIGN(const auto report, poll_status(link, pending));
    if (report) {
      status = *report;
    }
  }
  return status;
}

// Where the machine stands in the program's coordinates: the work position (the program runs
// in the active work offset), from WPos or MPos less WCO.
std::vector<double> program_position(const drivers::StatusReport& status, Logger& log) {
  auto p = status.machine_position;
  if (status.work_position) {
    return p;
  }
  if (!status.work_offset) {
    log.warning("the controller reported no work offset: its machine position is taken as the "
                "program's");
    return p;
  }
  for (std::size_t i = 0; i < std::min(p.size(), status.work_offset->size()); ++i) {
    p[i] -= (*status.work_offset)[i];
  }
  return p;
}

// The program from line `after` + 1, behind the restart blocks (journalled as line 0).
class ResumedProgram final : public drivers::LineSource {
public:
  ResumedProgram(drivers::GcodeSource file, std::vector<std::string> preamble, long after)
      : file_(std::move(file)), preamble_(std::move(preamble)), after_(after) {}
  [[nodiscard]] const std::string& name() const override { return file_.name(); }
  void set_rules(const drivers::LineRules& rules) override { file_.set_rules(rules); }
  [[nodiscard]] Expected<drivers::ScanSummary> scan() override { return drivers::ScanSummary{}; }
  [[nodiscard]] Expected<void> rewind() override {
    next_ = 0;
    return file_.rewind();
  }
  [[nodiscard]] Expected<std::optional<drivers::SourceLine>> next() override {
    if (next_ < preamble_.size()) {
      SUBFEED_TRY_ASSIGN(auto line, drivers::prepare_line(preamble_[next_++], file_.rules(),
                                                          {name(), 0, "resume"}));
      return drivers::SourceLine{0, std::move(line)};
    }
    while (true) {
      SUBFEED_TRY_ASSIGN(auto line, file_.next());
      if (!line || line->number > after_) {
        return line;
      }
    }
  }

private:
  drivers::GcodeSource file_;
  std::vector<std::string> preamble_;
  std::size_t next_ = 0;
  long after_;
};

Expected<void> ensure_program(const drivers::JournalSummary& j,
                              const std::optional<RunOptions>& job, Logger& log) {
  if (std::filesystem::exists(j.program)) {
    return {};
  }
  if (!job) {
    return fail(ErrorCode::bad_input,
                "the program is gone and the journal has no job to rebuild it", {j.program, 0, {}});
  }
  log.info(fmt::format("{} is missing (subfeed stopped before it was complete): planning and "
                       "posting it again",
                       j.program));
  SUBFEED_TRY_ASSIGN(auto spec, job_spec(*job, log));
  JobPipeline pipeline(std::move(spec));
  pipeline.detach();
  pipeline.start();
  SUBFEED_TRY(pipeline.finish());
  return {};
}

// A rebuilt program must be the one that was sent: the last line sent must have the bytes
// the journal recorded (as the streamer counted them: GRBL lines prepared, DNC blocks as
// written).
Expected<long> sent_bytes_of(const Interrupted& r, long line) {
  const auto& program = r.journal.program;
  if (r.dnc) {
    SUBFEED_TRY_ASSIGN(auto file, drivers::FanucProgram::open(program));
    drivers::FanucBlock block;
    while (true) {
      SUBFEED_TRY_ASSIGN(const bool more, file.next(block));
      if (!more || block.line > line) {
        return 0L;
      }
      if (block.line == line) {
        return static_cast<long>(block.text.size()) + 1;
      }
    }
  }
  SUBFEED_TRY_ASSIGN(
      auto file, drivers::GcodeSource::open(program, {r.machine.controller.line_length, false}));
  while (true) {
    SUBFEED_TRY_ASSIGN(const auto next, file.next());
    if (!next || next->number > line) {
      return 0L;
    }
    if (next->number == line) {
      return static_cast<long>(next->line.text.size()) + 1;
    }
  }
}

Expected<void> matches_journal(const Interrupted& r) {
  const auto& j = r.journal;
  if (j.last_sent == 0) {
    return {};
  }
  SUBFEED_TRY_ASSIGN(const long bytes, sent_bytes_of(r, j.last_sent));
  if (bytes == 0) {
    return fail(ErrorCode::bad_input,
                fmt::format("the program is shorter than the {} lines sent", j.last_sent),
                {j.program, 0, {}});
  }
  if (bytes != j.last_sent_bytes) {
    return fail(ErrorCode::bad_input,
                fmt::format("the program differs from the one sent: line {} has {} bytes, the "
                            "journal says {}",
                            j.last_sent, bytes, j.last_sent_bytes),
                {j.program, static_cast<int>(j.last_sent), {}});
  }
  return {};
}

Expected<Interrupted> read_interrupted(const ResumeOptions& o, Logger& log) {
  Interrupted r;
  SUBFEED_TRY_ASSIGN(r.journal, drivers::read_journal(o.journal));
  if (r.journal.finished) {
    return fail(ErrorCode::bad_input, "the job finished: nothing to resume", {o.journal, 0, {}});
  }
  r.dnc = r.journal.protocol == "fanuc";
  if (r.dnc && o.block < 0 && o.from == 0) {
    return fail(ErrorCode::usage,
                "a DNC control reports no position: give the sequence number it shows for the "
                "block it stopped in (--block N) or the program line (--from LINE)",
                {o.journal, 0, "--block"});
  }
  if (r.journal.job) {
    SUBFEED_TRY_ASSIGN(r.job, decode_job(*r.journal.job, {o.journal, 0, "job"}));
  }
  const std::string machine = !o.machine.empty() ? o.machine : r.job ? r.job->machine : "";
  if (machine.empty()) {
    return fail(ErrorCode::usage, "the journal names no machine", {{}, 0, "--machine"});
  }
  SUBFEED_TRY_ASSIGN(r.machine, post::load_machine_config(machine));
  SUBFEED_TRY(ensure_program(r.journal, r.job, log));
  SUBFEED_TRY(matches_journal(r));
  return r;
}

// --at X,Y,Z[,A..]: one number per axis of the machine, in X Y Z A B C order.
Expected<Joints> parse_position(const std::string& text, const post::MachineConfig& m) {
  std::vector<double> values;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    const auto value = parse_double(item);
    if (!value) {
      return fail(ErrorCode::usage, "'" + item + "' is not a number", {{}, 0, "--at"});
    }
    values.push_back(*value);
  }
  const auto axes = static_cast<std::size_t>(
      std::ranges::count_if(m.axes, [](const auto& a) { return a.has_value(); }));
  if (values.size() != axes) {
    return fail(ErrorCode::usage,
                fmt::format("expected {} positions (one per axis of the machine), got {}", axes,
                            values.size()),
                {{}, 0, "--at"});
  }
  Joints j{};
  auto next = values.begin();
  for (std::size_t i = 0; i < j.size(); ++i) {
    if (m.axes[i]) {
      j[i] = *next++;
    }
  }
  return j;
}

Expected<std::vector<std::string>> restart_blocks(const Interrupted& r, const ResumeOptions& o,
                                                  const ProgramWindow& w, long after,
                                                  const std::optional<Joints>& here) {
  const LineEnd& end = w.line_end.at(after);
  SUBFEED_TRY_ASSIGN(auto restore, restore_blocks(r.journal.program, after));
  Approach a;
  a.from = here;
  a.to = machine_joints(r.machine, end);
  a.tcp = end.tcp;
  a.clearance = o.clearance > 0.0 ? o.clearance
                : r.job           ? r.job->plan.clearance
                                  : r.machine.post.retract;
  a.feed = o.plunge_feed > 0.0 ? o.plunge_feed : r.job ? r.job->plan.plunge_feed : 300.0;
  // GRBL: restore, approach, restore (the approach changes modes). DNC: the streamer
  // restores before these.
  std::vector<std::string> blocks = r.dnc ? std::vector<std::string>{} : restore;
  for (auto& line : approach_blocks(r.machine, a)) {
    blocks.push_back(std::move(line));
  }
  blocks.insert(blocks.end(), restore.begin(), restore.end());
  return blocks;
}

Expected<Restart> grbl_restart(const Interrupted& r, const ResumeOptions& o,
                               const std::vector<double>& position) {
  const auto& j = r.journal;
  const long lo = std::max(1L, std::min(j.last_acked, j.last_sent) - planner_reach);
  SUBFEED_TRY_ASSIGN(const auto window,
                     read_window(j.program, lo, j.last_sent, o.from > 0 ? o.from - 1 : 0));
  Restart s;
  if (o.from > 0) {
    s.after = o.from - 1;
    s.why = "as asked (--from)";
  } else if (const auto at = find_machine(window, position, r.machine.controller.decimals)) {
    s.after = at->after;
    s.why = at->mid_block ? "the machine stopped inside the next line's move: it runs again "
                            "from its start"
                          : "the machine stands at the end of that line";
  } else {
    s.after = lo - 1;
    s.why = fmt::format("the machine is on no move near the last acknowledged line {}: up to {} "
                        "lines may be cut again",
                        j.last_acked, j.last_sent - lo + 1);
  }
  Joints here{};
  for (std::size_t i = 0; i < std::min<std::size_t>(6, position.size()); ++i) {
    here[i] = position[i];
  }
  SUBFEED_TRY_ASSIGN(s.blocks, restart_blocks(r, o, window, s.after, here));
  return s;
}

// Asks the controller, once the machine stands still, where it is, and restarts there.
Expected<Restart> grbl_restart_found(drivers::Transport& link, const Interrupted& r,
                                     const ResumeOptions& o, Logger& log) {
  SUBFEED_TRY(wait_until_still(link, o, log));
  SUBFEED_TRY_ASSIGN(auto status, probe(link, o));
  SUBFEED_TRY_ASSIGN(status, with_work_offset(link, std::move(status), 40));
  if (status.state == "Alarm") {
    return fail(ErrorCode::machine_fault,
                "the controller is in alarm: home it ($H) or unlock it ($X), then resume again",
                {o.journal, 0, {}});
  }
  return grbl_restart(r, o, program_position(status, log));
}

Expected<Restart> dnc_restart(const Interrupted& r, const ResumeOptions& o) {
  const auto& j = r.journal;
  Restart s;
  if (o.from > 0) {
    s.after = o.from - 1;
    s.why = "as asked (--from)";
  } else {
    SUBFEED_TRY_ASSIGN(const long line, find_sequence_number(j.program, o.block, j.last_sent));
    s.after = line - 1;
    s.why = line > j.last_sent
                ? fmt::format("block N{}, the first not sent, runs from its start", o.block)
                : fmt::format("block N{} runs again from its start", o.block);
  }
  std::optional<Joints> here;
  if (!o.at.empty()) {
    SUBFEED_TRY_ASSIGN(here, parse_position(o.at, r.machine));
  } else if (!tool_axis_fixed(r.machine)) {
    return fail(ErrorCode::usage,
                "the tool tilts with the head: give the machine position the control shows, so "
                "that the retract follows the tool's axis",
                {{}, 0, "--at"});
  }
  SUBFEED_TRY_ASSIGN(const auto window, read_window(j.program, s.after, s.after, s.after));
  SUBFEED_TRY_ASSIGN(s.blocks, restart_blocks(r, o, window, s.after, here));
  return s;
}

bool confirmed(const ResumeOptions& o) {
  if (o.yes) {
    return true;
  }
  if (::isatty(STDIN_FILENO) == 0) {
    return false;
  }
  std::cerr << "Move the machine and continue? [y/N] " << std::flush;
  std::string answer;
  std::getline(std::cin, answer);
  return answer == "y" || answer == "Y" || answer == "yes";
}

void show(const Restart& s, const Interrupted& r, const ResumeOptions& o, Logger& log) {
  const auto& j = r.journal;
  log.info(fmt::format(
      "resume {}: continue after line {} ({}); last sent {}{}", o.journal, s.after, s.why,
      j.last_sent, r.dnc ? std::string() : fmt::format(", last acknowledged {}", j.last_acked)));
  log.info("  before it, these blocks restore the modes and approach safely:");
  for (const auto& line : s.blocks) {
    log.info("    " + line);
  }
}

Expected<drivers::StreamSummary> stream_grbl_rest(const Interrupted& r, Restart s, Link& link,
                                                  drivers::ControlInbox& inbox,
                                                  drivers::StreamObserver& observer) {
  SUBFEED_TRY_ASSIGN(auto file, drivers::GcodeSource::open(r.journal.program, {}));
  ResumedProgram source(std::move(file), std::move(s.blocks), s.after);
  drivers::GrblStreamOptions options;
  options.line_limit = r.machine.controller.line_length;
  options.rx_buffer = r.machine.controller.rx_buffer;
  return drivers::stream_grbl(*link.transport, source, options, &inbox, observer);
}

Expected<drivers::StreamSummary> stream_dnc_rest(const Interrupted& r, Restart s, Link& link,
                                                 drivers::ControlInbox& inbox,
                                                 drivers::StreamObserver& observer) {
  SUBFEED_TRY_ASSIGN(auto program, drivers::FanucProgram::open(r.journal.program));
  drivers::FanucStreamOptions options;
  options.serial = serial_options_for(r.machine);
  options.program_number = r.machine.controller.program_number;
  options.from_line = s.after + 1;
  options.restart_blocks = std::move(s.blocks);
  return drivers::stream_fanuc(*link.transport, program, options, &inbox, observer);
}

Expected<void> resume(const ResumeOptions& o, Logger& log) {
  block_stop_signals();
  SUBFEED_TRY_ASSIGN(const auto r, read_interrupted(o, log));
  const std::string protocol = r.dnc ? "fanuc" : "grbl";
  if (r.dnc && !o.tcp.empty()) {
    return fail(ErrorCode::usage, "DNC drip feed runs over a serial port, not --tcp",
                {{}, 0, "--tcp"});
  }
  LinkRequest request;
  request.port = o.port;
  request.tcp = o.tcp;
  request.protocol = protocol;
  request.connect_timeout_s = o.connect_timeout_s;
  const auto serial = serial_options_for(r.machine);
  Restart restart;
  if (r.dnc) { // the user's words alone: checked before the port is touched
    SUBFEED_TRY_ASSIGN(restart, dnc_restart(r, o));
  }
  SUBFEED_TRY_ASSIGN(auto link, open_link(request, serial));
  if (!r.dnc) {
    SUBFEED_TRY_ASSIGN(restart, grbl_restart_found(*link.transport, r, o, log));
  }
  show(restart, r, o, log);
  if (!confirmed(o)) {
    return fail(ErrorCode::stopped, "not confirmed: nothing was sent (use --yes to skip asking)",
                {o.journal, 0, {}});
  }
  SUBFEED_TRY_ASSIGN(auto journal, drivers::Journal::open(o.journal));
  SUBFEED_TRY_ASSIGN(auto inbox, drivers::ControlInbox::create());
  StreamReporter reporter(log, false);
  drivers::JournaledObserver observer(reporter, journal);
  journal.start(protocol, r.journal.program, link.transport->name());
  journal.event("resume", fmt::format("after={}", restart.after));
  const ControlThread control(*inbox, true);
  const auto summary = r.dnc ? stream_dnc_rest(r, std::move(restart), link, *inbox, observer)
                             : stream_grbl_rest(r, std::move(restart), link, *inbox, observer);
  journal.end(summary);
  if (!summary) {
    reporter.failed(summary.error());
    return std::unexpected(summary.error());
  }
  reporter.finished(*summary, link.baud, drivers::bits_per_character(serial));
  return {};
}

} // namespace

void add_resume_command(CLI::App& app, Action& chosen) {
  auto o = std::make_shared<ResumeOptions>();
  CLI::App* cmd = app.add_subcommand("resume", "Continue a job from its journal after a fault");
  cmd->add_option("journal", o->journal, "The job's journal")->required()->type_name("JOB.journal");
  auto* link = cmd->add_option_group("link", "Where the controller is (exactly one)");
  link->add_option("--port", o->port, "Serial port")->type_name("DEV");
  link->add_option("--tcp", o->tcp, "TCP stream")->type_name("HOST:PORT");
  link->require_option(1);
  cmd->add_option("--machine", o->machine, "Machine config (default: the job's)")
      ->type_name("M.toml");
  cmd->add_option("--from", o->from, "Continue from this program line instead")
      ->check(positive_number());
  cmd->add_option("--block", o->block,
                  "DNC: the sequence number the control shows for the block it stopped in")
      ->check(non_negative_number());
  cmd->add_option("--at", o->at,
                  "DNC: the machine position the control shows, X,Y,Z[,A,B,C] (needed where "
                  "the tool tilts with the head)")
      ->type_name("X,Y,Z,...");
  cmd->add_flag("--yes", o->yes, "Do not ask before moving the machine");
  cmd->add_option("--clearance", o->clearance, "Retract along the tool axis, mm")
      ->check(CLI::Range(0.01, 1000.0));
  cmd->add_option("--plunge-feed", o->plunge_feed, "Feed of the retract and the plunge, mm/min")
      ->check(CLI::Range(1.0, 100000.0));
  cmd->add_option("--connect-timeout", o->connect_timeout_s, "Seconds to wait for the controller")
      ->check(CLI::Range(0.1, 600.0));
  cmd->callback([&chosen, o] { chosen = [o](Logger& log) { return resume(*o, log); }; });
}

} // namespace subfeed::cli
