// `subfeed resume JOURNAL (--port DEV | --tcp HOST:PORT)`: continues a GRBL job after a lost
// link, an alarm or a crash of subfeed itself. Where to continue: the controller is asked
// where the machine stands, and that position is looked up among the program's block ends
// between the last acknowledged and the last sent line (a controller that survived ran
// what it had received; GRBL keeps its position through a reset from Idle or Hold). When the
// position is on no block end (the controller lost its position, or stopped mid-block), the
// resume starts from the last acknowledged line less what a planner can hold, so that no
// block is skipped, and says how many may be cut twice. --from LINE overrides.
//
// Before the program continues: the modal state it had built up (units, plane, distance
// mode, feed mode and feed, spindle, coolant) is restored, the tool retracts along its axis
// by the clearance, rises to the safe Z, the rotary axes turn, X Y position above the
// restart point, and the tool plunges along its axis to it. All of it is shown first and
// sent only after a yes (or --yes).

#include "command.hpp"
#include "control_thread.hpp"
#include "controller_link.hpp"
#include "job_pipeline.hpp"
#include "run_job.hpp"
#include "stream_reporter.hpp"

#include "drivers/fanuc_modal_state.hpp"
#include "drivers/fanuc_streamer.hpp"
#include "drivers/gcode_source.hpp"
#include "drivers/grbl_streamer.hpp"
#include "drivers/journal.hpp"
#include "drivers/journal_reader.hpp"
#include "drivers/live_program.hpp"
#include "post/kinematics.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <iostream>
#include <map>
#include <unistd.h>

namespace subfeed::cli {

namespace {

constexpr long planner_reach = 128; // lines a GRBL-style planner (and its RX buffer) can hold

struct ResumeOptions {
  std::string journal;
  std::string port, tcp;
  std::string machine;
  long from = 0;
  bool yes = false;
  double clearance = 0.0; // mm; 0: the job's clearance, else the machine's retract
  double plunge_feed = 0.0;
  double connect_timeout_s = 5.0;
};

using Joints = post::JointPosition;

// Axis words of one program line onto the joints (absolute mode, as subfeed posts).
void apply_axis_words(std::string_view line, Joints& joints) {
  bool comment = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (comment || c == '(') {
      comment = c != ')';
      continue;
    }
    const auto axis = post::axis_letters.find(c);
    if (axis == std::string_view::npos) {
      continue;
    }
    char* end = nullptr;
    const std::string rest(line.substr(i + 1, 24));
    const double value = std::strtod(rest.c_str(), &end);
    if (end != rest.c_str()) {
      joints[axis] = value;
    }
  }
}

struct Move {
  long line;
  Joints start, end;
};

struct ProgramState {
  long lines = 0;
  std::vector<Move> moves;                  // the motion lines searched for the machine
  std::map<long, Joints> joints_after_line; // for those lines, the line before, and `extra`
};

// The program's joints line by line; lines lo..hi are searched, `extra` is a line whose end
// position is wanted too (--from).
Expected<ProgramState> read_positions(const std::string& program, long lo, long hi, long extra) {
  std::ifstream in(program);
  if (!in) {
    return fail(ErrorCode::bad_input, "cannot read the program", {program, 0, {}});
  }
  ProgramState s;
  Joints joints{};
  std::string text;
  while (std::getline(in, text)) {
    ++s.lines;
    const Joints before = joints;
    apply_axis_words(text, joints);
    if ((s.lines >= lo - 1 && s.lines <= hi) || s.lines == extra) {
      s.joints_after_line[s.lines] = joints;
    }
    const bool moves = text.find_first_of("XYZABC") != std::string::npos;
    if (s.lines >= lo && s.lines <= hi && moves) {
      s.moves.push_back({s.lines, before, joints});
    }
  }
  if (extra > 0 && !s.joints_after_line.contains(extra)) {
    s.joints_after_line[extra] = joints; // --from past the end: nothing is left to run
  }
  if (!s.joints_after_line.contains(lo - 1)) {
    s.joints_after_line[lo - 1] = Joints{};
  }
  return s;
}

// Where along the move from `m.start` to `m.end` (joints interpolated linearly, as the
// control does) the reported position lies, 0..1; none when it is off the move by more than
// the rounding of the program's words and the status report's (GRBL reports 3 decimals).
std::optional<double> place_on_move(const Move& m, const std::vector<double>& mpos, int decimals) {
  const double tolerance = 0.75 * std::pow(10.0, -std::min(decimals, 3));
  const std::size_t n = std::min<std::size_t>(6, mpos.size());
  double along = 0.0, length2 = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    along += (mpos[i] - m.start[i]) * (m.end[i] - m.start[i]);
    length2 += (m.end[i] - m.start[i]) * (m.end[i] - m.start[i]);
  }
  const double t = length2 > 0.0 ? std::clamp(along / length2, 0.0, 1.0) : 1.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (std::abs(m.start[i] + t * (m.end[i] - m.start[i]) - mpos[i]) > tolerance) {
      return std::nullopt;
    }
  }
  return t;
}

struct RestartPoint {
  long after = 0;         // continue with the line after this one
  bool mid_block = false; // the machine stopped inside the next move
};

// The latest line the machine can be at: at the end of a move (continue after it) or inside
// one (run it again from its start: the part of it already cut is cut again, nothing is
// skipped). A controller that ran everything it received stands at the last line sent.
std::optional<RestartPoint> find_machine(const ProgramState& p, const std::vector<double>& mpos,
                                         int decimals) {
  std::optional<RestartPoint> found;
  for (const auto& m : p.moves) {
    const auto t = place_on_move(m, mpos, decimals);
    if (!t) {
      continue;
    }
    const bool at_end = *t >= 1.0 || place_on_move({m.line, m.end, m.end}, mpos, decimals);
    const RestartPoint here{at_end ? m.line : m.line - 1, !at_end};
    if (!found || here.after >= found->after) {
      found = here;
    }
  }
  return found;
}

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

std::string word(char letter, double value, int decimals) {
  return fmt::format("{}{:.{}f}", letter, value, decimals);
}

std::string move_line(const char* g, const Joints& j, const post::AxisSet& axes,
                      std::initializer_list<std::size_t> which, int decimals) {
  std::string line = g;
  for (const auto i : which) {
    if (axes[i]) {
      line += ' ' + word(post::axis_letters[i], j[i], i < 3 ? decimals : decimals + 1);
    }
  }
  return line;
}

// The joint solution nearest `near`, rotary axes taken on the turn nearest theirs.
Joints nearest(const post::Kinematics& k, const post::ToolPose& pose, const Joints& near) {
  Joints best = near;
  double best_d = INFINITY;
  for (auto c : k.inverse(pose, near)) {
    for (std::size_t i = 3; i < 6; ++i) {
      c[i] += 360.0 * std::round((near[i] - c[i]) / 360.0);
    }
    double d = 0.0;
    for (std::size_t i = 0; i < 6; ++i) {
      d += (c[i] - near[i]) * (c[i] - near[i]);
    }
    if (d < best_d) {
      best_d = d;
      best = c;
    }
  }
  return best;
}

post::ToolPose along_axis(post::ToolPose pose, double distance) {
  for (std::size_t i = 0; i < 3; ++i) {
    pose.tip[i] += distance * pose.axis[i];
  }
  return pose;
}

// Retract along the tool axis, safe Z, turn, position, plunge along the axis.
std::vector<std::string> approach(const post::MachineConfig& m, const Joints& from,
                                  const Joints& to, double clearance, double plunge_feed) {
  const auto k = post::make_kinematics(m);
  const int d = m.controller.decimals;
  const double safe_z = m.post.safe_z.value_or(m.axes[2]->max);
  const Joints retract = nearest(*k, along_axis(k->forward(from), clearance), from);
  Joints up = retract;
  up[2] = std::max(safe_z, retract[2]);
  Joints turned = up;
  for (std::size_t i = 3; i < 6; ++i) {
    turned[i] = to[i];
  }
  const Joints above = nearest(*k, along_axis(k->forward(to), clearance), to);
  Joints over = above;
  over[2] = up[2];
  const std::string f = fmt::format(" F{:.0f}", plunge_feed);
  return {"G94",
          move_line("G1", retract, m.axes, {0, 1, 2, 3, 4, 5}, d) + f,
          move_line("G0", up, m.axes, {2}, d),
          move_line("G0", turned, m.axes, {3, 4, 5}, d),
          move_line("G0", over, m.axes, {0, 1}, d),
          move_line("G0", above, m.axes, {0, 1, 2, 3, 4, 5}, d),
          move_line("G1", to, m.axes, {0, 1, 2, 3, 4, 5}, d) + f};
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
// the journal recorded.
Expected<void> matches_journal(const drivers::JournalSummary& j, int line_limit) {
  if (j.last_sent == 0) {
    return {};
  }
  SUBFEED_TRY_ASSIGN(auto file, drivers::GcodeSource::open(j.program, {line_limit, false}));
  while (true) {
    SUBFEED_TRY_ASSIGN(const auto line, file.next());
    if (!line || line->number > j.last_sent) {
      break;
    }
    if (line->number == j.last_sent) {
      const long bytes = static_cast<long>(line->line.text.size()) + 1;
      if (bytes == j.last_sent_bytes) {
        return {};
      }
      return fail(ErrorCode::bad_input,
                  fmt::format("the program differs from the one sent: line {} has {} bytes, the "
                              "journal says {}",
                              j.last_sent, bytes, j.last_sent_bytes),
                  {j.program, static_cast<int>(j.last_sent), {}});
    }
  }
  return fail(ErrorCode::bad_input,
              fmt::format("the program is shorter than the {} lines sent", j.last_sent),
              {j.program, 0, {}});
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

Expected<void> resume(const ResumeOptions& o, Logger& log) {
  block_stop_signals();
  SUBFEED_TRY_ASSIGN(const auto j, drivers::read_journal(o.journal));
  if (j.finished) {
    return fail(ErrorCode::bad_input, "the job finished: nothing to resume", {o.journal, 0, {}});
  }
  if (j.protocol != "grbl") {
    return fail(ErrorCode::usage,
                "DNC jobs report no position: position the tool, then `subfeed send " + j.program +
                    " --protocol fanuc --from LINE` (the block on the control)",
                {o.journal, 0, {}});
  }
  std::optional<RunOptions> job;
  if (j.job) {
    SUBFEED_TRY_ASSIGN(job, decode_job(*j.job, {o.journal, 0, "job"}));
  }
  const std::string machine_path = !o.machine.empty() ? o.machine : job ? job->machine : "";
  if (machine_path.empty()) {
    return fail(ErrorCode::usage, "the journal names no machine", {{}, 0, "--machine"});
  }
  SUBFEED_TRY_ASSIGN(const auto machine, post::load_machine_config(machine_path));
  SUBFEED_TRY(ensure_program(j, job, log));
  SUBFEED_TRY(matches_journal(j, machine.controller.line_length));
  LinkRequest request;
  request.port = o.port;
  request.tcp = o.tcp;
  request.protocol = "grbl";
  request.connect_timeout_s = o.connect_timeout_s;
  const auto serial = serial_options_for(machine);
  SUBFEED_TRY_ASSIGN(auto link, open_link(request, serial));
  SUBFEED_TRY_ASSIGN(const auto status, probe(*link.transport, o));
  if (status.state == "Alarm") {
    return fail(ErrorCode::machine_fault,
                "the controller is in alarm: home it ($H) or unlock it ($X), then resume again",
                {o.journal, 0, {}});
  }
  const long lo = std::max(1L, std::min(j.last_acked, j.last_sent) - planner_reach);
  SUBFEED_TRY_ASSIGN(const auto program,
                     read_positions(j.program, lo, j.last_sent, o.from > 0 ? o.from - 1 : 0));
  long after = 0;
  std::string why;
  if (o.from > 0) {
    after = o.from - 1;
    why = "as asked (--from)";
  } else if (const auto at =
                 find_machine(program, status.machine_position, machine.controller.decimals)) {
    after = at->after;
    why = at->mid_block ? "the machine stopped inside the next line's move: it runs again "
                          "from its start"
                        : "the machine stands at the end of that line";
  } else {
    after = lo - 1;
    why = fmt::format("the machine is on no move near the last acknowledged line {}: up to {} "
                      "lines may be cut again",
                      j.last_acked, j.last_sent - lo + 1);
  }
  const Joints target = program.joints_after_line.at(after);
  Joints here{};
  for (std::size_t i = 0; i < std::min<std::size_t>(6, status.machine_position.size()); ++i) {
    here[i] = status.machine_position[i];
  }
  drivers::FanucModalState modal;
  {
    std::ifstream in(j.program);
    std::string text;
    for (long n = 1; n <= after && std::getline(in, text); ++n) {
      modal.apply(text);
    }
  }
  SUBFEED_TRY_ASSIGN(auto restore,
                     modal.restore_blocks({j.program, static_cast<int>(after + 1), {}}));
  const double clearance = o.clearance > 0.0 ? o.clearance
                           : job             ? job->plan.clearance
                                             : machine.post.retract;
  const double plunge = o.plunge_feed > 0.0 ? o.plunge_feed : job ? job->plan.plunge_feed : 300.0;
  std::vector<std::string> preamble = restore;
  for (auto& line : approach(machine, here, target, clearance, plunge)) {
    preamble.push_back(std::move(line));
  }
  preamble.insert(preamble.end(), restore.begin(), restore.end());
  log.info(fmt::format("resume {}: continue after line {} of {} ({}); last sent {}, last "
                       "acknowledged {}",
                       o.journal, after, program.lines, why, j.last_sent, j.last_acked));
  log.info("  before it, these blocks restore the modes and approach safely:");
  for (const auto& line : preamble) {
    log.info("    " + line);
  }
  if (!confirmed(o)) {
    return fail(ErrorCode::stopped, "not confirmed: nothing was sent (use --yes to skip asking)",
                {o.journal, 0, {}});
  }
  SUBFEED_TRY_ASSIGN(auto file, drivers::GcodeSource::open(j.program, {}));
  ResumedProgram source(std::move(file), std::move(preamble), after);
  SUBFEED_TRY_ASSIGN(auto journal, drivers::Journal::open(o.journal));
  SUBFEED_TRY_ASSIGN(auto inbox, drivers::ControlInbox::create());
  StreamReporter reporter(log, false);
  drivers::JournaledObserver observer(reporter, journal);
  journal.start("grbl", j.program, link.transport->name());
  journal.event("resume", fmt::format("after={}", after));
  const ControlThread control(*inbox, true);
  drivers::GrblStreamOptions options;
  options.line_limit = machine.controller.line_length;
  options.rx_buffer = machine.controller.rx_buffer;
  const auto summary =
      drivers::stream_grbl(*link.transport, source, options, inbox.get(), observer);
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
      ->check(CLI::PositiveNumber);
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
