// `subfeed resume JOURNAL (--port DEV | --tcp HOST:PORT)`: continues a job after a lost link,
// an alarm, a dead controller or a crash of subfeed itself. Where and how it continues is the
// job library's (job/restart_plan.hpp); this command shows it, asks, and streams.

#include "command.hpp"
#include "job/control_thread.hpp"
#include "option_checks.hpp"
#include "setup_flags.hpp"
#include "stream_reporter.hpp"

#include "job/restart_plan.hpp"

#include "drivers/fanuc_streamer.hpp"
#include "drivers/journal.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <iostream>
#include <unistd.h>

namespace subfeed::cli {

using namespace subfeed::job; // NOLINT: the front wires the job library

namespace {

struct ResumeOptions {
  ResumeRequest request;
  std::string port, tcp;
  bool yes = false;
};

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
      "resume {}: continue after line {} ({}); last sent {}{}", o.request.journal, s.after, s.why,
      j.last_sent, r.dnc ? std::string() : fmt::format(", last acknowledged {}", j.last_acked)));
  log.info("  before it, these blocks restore the modes and approach safely:");
  for (const auto& line : s.blocks) {
    log.info("    " + line);
  }
}

Expected<void> resume(const ResumeOptions& o, Logger& log) {
  block_stop_signals();
  SUBFEED_TRY_ASSIGN(const auto r, read_interrupted(o.request, log));
  const std::string protocol = r.dnc ? "fanuc" : "grbl";
  if (r.dnc && !o.tcp.empty()) {
    return fail(ErrorCode::usage, "DNC drip feed runs over a serial port, not --tcp",
                {{}, 0, "--tcp"});
  }
  LinkRequest request;
  request.port = o.port;
  request.tcp = o.tcp;
  request.protocol = protocol;
  request.connect_timeout_s = o.request.connect_timeout_s;
  const auto serial = serial_options_for(r.machine);
  Restart restart;
  if (r.dnc) { // the user's words alone: checked before the port is touched
    SUBFEED_TRY_ASSIGN(restart, dnc_restart(r, o.request));
  }
  SUBFEED_TRY_ASSIGN(auto link, open_link(request, serial));
  if (!r.dnc) {
    SUBFEED_TRY_ASSIGN(restart, grbl_restart_found(*link.transport, r, o.request, log));
  }
  show(restart, r, o, log);
  if (!confirmed(o)) {
    return fail(ErrorCode::stopped, "not confirmed: nothing was sent (use --yes to skip asking)",
                {o.request.journal, 0, {}});
  }
  SUBFEED_TRY_ASSIGN(auto journal, drivers::Journal::open(o.request.journal));
  SUBFEED_TRY_ASSIGN(auto inbox, drivers::ControlInbox::create());
  StreamReporter reporter(log, false);
  drivers::JournaledObserver observer(reporter, journal);
  journal.start(protocol, r.journal.program, link.transport->name());
  journal.event("resume", fmt::format("after={}", restart.after));
  const ControlThread control(*inbox, true);
  const auto summary = stream_rest(r, std::move(restart), link, *inbox, observer);
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
  cmd->add_option("journal", o->request.journal, "The job's journal")
      ->required()
      ->type_name("JOB.journal");
  auto* link = cmd->add_option_group("link", "Where the controller is (exactly one)");
  link->add_option("--port", o->port, "Serial port")->type_name("DEV");
  link->add_option("--tcp", o->tcp, "TCP stream")->type_name("HOST:PORT");
  link->require_option(1);
  cmd->add_option("--machine", o->request.machine, "Machine config (default: the job's)")
      ->type_name("M.toml");
  cmd->add_option("--from", o->request.from, "Continue from this program line instead")
      ->check(positive_number());
  cmd->add_option("--block", o->request.block,
                  "DNC: the sequence number the control shows for the block it stopped in")
      ->check(non_negative_number());
  cmd->add_option("--at", o->request.at,
                  "DNC: the machine position the control shows, X,Y,Z[,A,B,C] (needed where "
                  "the tool tilts with the head)")
      ->type_name("X,Y,Z,...");
  cmd->add_flag("--yes", o->yes, "Do not ask before moving the machine");
  add_setup_flags(*cmd, o->request.setup);
  cmd->add_option("--clearance", o->request.clearance, "Retract along the tool axis, mm")
      ->check(CLI::Range(0.01, 1000.0));
  cmd->add_option("--plunge-feed", o->request.plunge_feed,
                  "Feed of the retract and the plunge, mm/min")
      ->check(CLI::Range(1.0, 100000.0));
  cmd->add_option("--connect-timeout", o->request.connect_timeout_s,
                  "Seconds to wait for the controller")
      ->check(CLI::Range(0.1, 600.0));
  cmd->callback([&chosen, o] { chosen = [o](Logger& log) { return resume(*o, log); }; });
}

} // namespace subfeed::cli
