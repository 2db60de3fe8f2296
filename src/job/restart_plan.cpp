#include "job/restart_plan.hpp"

#include "base/number_text.hpp"
#include "job/job_pipeline.hpp"
#include "job/restart_approach.hpp"
#include "job/restart_point.hpp"

#include "cl/cl_reader.hpp"
#include "drivers/fanuc_program.hpp"
#include "drivers/fanuc_streamer.hpp"
#include "drivers/gcode_source.hpp"
#include "drivers/grbl_status_poll.hpp"
#include "drivers/grbl_streamer.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <sstream>
#include <utility>

namespace subfeed::job {

namespace {

constexpr long planner_reach = 128; // lines a GRBL-style planner (and its RX buffer) can hold

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

Expected<void> ensure_program(const drivers::JournalSummary& j, const std::optional<JobRecord>& job,
                              Logger& log) {
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

Expected<std::vector<std::string>> restart_blocks(const Interrupted& r, const ResumeRequest& o,
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

Expected<Restart> grbl_restart(const Interrupted& r, const ResumeRequest& o,
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
// A setup said on resume's command line must be the one the job ran with.
Expected<void> setup_agrees(const ResumeRequest& o, const std::optional<JobRecord>& job) {
  if (!o.setup.any()) {
    return {};
  }
  if (!job) {
    return fail(ErrorCode::usage, "the journal keeps no job, so no setup to check against",
                {o.journal, 0, "--up"});
  }
  std::string recorded = geometry::setup_text(job->setup.with_defaults());
  if (reads_cl(*job)) {
    SUBFEED_TRY_ASSIGN(const auto reader, cl::ClReader::open(job->cage));
    SUBFEED_TRY_ASSIGN(const auto kept, agreed_setup(job->setup, reader.header().setup, job->cage));
    recorded = geometry::setup_text(kept);
  }
  SUBFEED_TRY(agreed_setup(o.setup, recorded, o.journal));
  return {};
}

} // namespace

Expected<Interrupted> read_interrupted(const ResumeRequest& o, Logger& log) {
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
  SUBFEED_TRY(setup_agrees(o, r.job));
  const std::string machine = !o.machine.empty() ? o.machine : r.job ? r.job->machine : "";
  if (machine.empty()) {
    return fail(ErrorCode::usage, "the journal names no machine", {{}, 0, "--machine"});
  }
  SUBFEED_TRY_ASSIGN(r.machine, post::load_machine_config(machine));
  SUBFEED_TRY(ensure_program(r.journal, r.job, log));
  SUBFEED_TRY(matches_journal(r));
  return r;
}

Expected<Restart> grbl_restart_found(drivers::Transport& link, const Interrupted& r,
                                     const ResumeRequest& o, Logger& log) {
  const auto timeout = std::chrono::milliseconds(static_cast<long>(o.connect_timeout_s * 1e3));
  drivers::StatusPoller poller(link);
  SUBFEED_TRY(
      poller.wait_until_still(timeout, std::chrono::minutes(10), [&log](const std::string& state) {
        log.info("the machine is still moving (" + state + "): waiting for it to stop");
      }));
  SUBFEED_TRY_ASSIGN(auto status, drivers::probe_status(link, timeout));
  SUBFEED_TRY_ASSIGN(status, poller.with_work_offset(std::move(status), 40));
  if (status.state == "Alarm") {
    return fail(ErrorCode::machine_fault,
                "the controller is in alarm: home it ($H) or unlock it ($X), then resume again",
                {o.journal, 0, {}});
  }
  return grbl_restart(r, o, program_position(status, log));
}

Expected<Restart> dnc_restart(const Interrupted& r, const ResumeRequest& o) {
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

Expected<drivers::StreamSummary> stream_rest(const Interrupted& r, Restart restart, Link& link,
                                             drivers::ControlInbox& inbox,
                                             drivers::StreamObserver& observer) {
  return r.dnc ? stream_dnc_rest(r, std::move(restart), link, inbox, observer)
               : stream_grbl_rest(r, std::move(restart), link, inbox, observer);
}

} // namespace subfeed::job
