// `subfeed run CAGE.obj --machine M.toml --tool ball:D --scallop H (--port | --tcp | --sim)`:
// the whole job, lazily chained (job_pipeline.hpp): the controller receives the program's
// first blocks while the planner is still solving, and memory stays bounded. The .cl, .nc
// and .nc.map appear beside the cage (or -o BASE) once complete; the journal records every
// block sent and answered, and the job's own arguments so that `resume` can rebuild it.

#include "command.hpp"
#include "job/control_thread.hpp"
#include "job/controller_link.hpp"
#include "job/dry_run.hpp"
#include "job/job_pipeline.hpp"
#include "job/job_record.hpp"
#include "job/job_stream.hpp"
#include "job_reporter.hpp"
#include "option_checks.hpp"
#include "plan_flags.hpp"
#include "plan_report.hpp"
#include "setup_flags.hpp"

#include "drivers/fanuc_streamer.hpp"
#include "drivers/grbl_streamer.hpp"
#include "drivers/journal.hpp"
#include "geometry/obj_reader.hpp"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <fmt/format.h>

namespace subfeed::cli {

using namespace subfeed::job; // NOLINT: the front wires the job library

namespace {

void add_run_flags(CLI::App& cmd, job::JobRecord& o) {
  add_plan_flags(cmd, o.plan, false);
  add_setup_flags(cmd, o.setup);
  cmd.add_option("--machine", o.machine, "Machine config: kinematics, limits, controller")
      ->required()
      ->type_name("M.toml");
  cmd.add_option("-o,--output", o.output,
                 "BASE of the files written: BASE.cl, BASE.nc, BASE.nc.map, BASE.journal "
                 "(default: the cage's path without .obj)");
  cmd.add_option("--journal", o.journal, "Append the job's journal to FILE (default BASE.journal)")
      ->type_name("FILE");
  cmd.add_option("--cage", o.check_cage,
                 "With CL data: the cage it was made for; every move is checked against it "
                 "before it is streamed (required)")
      ->type_name("CAGE.obj");
  cmd.add_option("--spindle", o.spindle_rpm, "Spindle speed, rpm (S and M3 at the start)")
      ->check(CLI::Range(0.0, 200000.0));
}

void report_totals(const JobTotals& t, const JobFiles& files, const JobReporter& reporter,
                   bool json, Logger& log) {
  report_left_material(t.plan, log);
  if (json) {
    std::printf("{\"event\":\"job\",\"passes\":%ld,\"cl_points\":%ld,\"lines\":%ld,"
                "\"cut_mm\":%.3f,\"machine_min\":%.3f,\"first_block_s\":%.4f,"
                "\"first_move_s\":%.4f,\"streamed_s\":%.4f}\n",
                t.plan.passes, t.plan.points, t.lines, t.cut_mm, t.machine_min,
                reporter.first_block_s().value_or(-1.0), reporter.first_move_s().value_or(-1.0),
                reporter.streamed_s());
    std::fflush(stdout);
    return;
  }
  log.info(fmt::format("{}: {} passes, cutting {:.1f} mm; {}: {} lines, modelled machine time "
                       "{:.1f} min",
                       files.cl.string(), t.plan.passes, t.cut_mm, files.nc.string(), t.lines,
                       t.machine_min));
  if (t.posted_gate.moves > 0) {
    log.info(posted_gate_summary(t.posted_gate));
  }
  if (t.plan.times.total_s() > 0.0) { // planned here, not read from CL data
    log.detail(time_summary(t.plan.times, t.plan.solves));
  }
  if (reporter.first_block_s() && reporter.first_move_s()) {
    log.info(fmt::format("  first block reached the controller {:.3f} s after start, the first "
                         "move {:.3f} s after start",
                         *reporter.first_block_s(), *reporter.first_move_s()));
  }
}

Expected<void> run_job(JobRecord o, Logger& log) {
  block_stop_signals();                   // before any thread starts
  SUBFEED_TRY(resolve_tool(o.plan, log)); // the journal keeps the sizes, not the name
  SUBFEED_TRY_ASSIGN(auto spec, job_spec(o, log));
  const auto machine = spec.machine;
  const JobFiles files = spec.files;
  const double tolerance = spec.post.post.tolerance;
  const bool fanuc = machine.controller.protocol == post::Protocol::fanuc;
  SUBFEED_TRY_ASSIGN(auto journal, drivers::Journal::open(journal_path(o)));
  const LinkRequest request = link_request_for(o, machine);
  const auto serial = serial_options_for(machine);
  SUBFEED_TRY_ASSIGN(auto link, open_link(request, serial));
  SUBFEED_TRY_ASSIGN(auto inbox, drivers::ControlInbox::create());
  JobPipeline job(std::move(spec));
  JobReporter reporter(log, o.json, job, !fanuc, o.sim ? o.sim_speed : 1.0);
  drivers::JournaledObserver observer(reporter, journal);
  journal.start(request.protocol, files.nc.string(), link.transport->name());
  journal.event("job", encode_job(o));
  const ControlThread control(*inbox, !o.json);
  job.start();
  const auto summary = stream_job(o, request.sim_baud, machine, link, job, *inbox, observer);
  journal.end(summary);
  if (!summary) {
    const Error error = with_simulated_alarm(summary.error(), link);
    reporter.failed(error);
    job.detach();
    if (const auto done = job.finish(); done) {
      log.warning(fmt::format("the program is complete in {}: `subfeed resume {}` continues "
                              "the job",
                              files.nc.string(), journal_path(o).string()));
    }
    return std::unexpected(error);
  }
  SUBFEED_TRY_ASSIGN(const auto totals, job.finish());
  reporter.finished(*summary, link.baud, drivers::bits_per_character(serial));
  report_totals(totals, files, reporter, o.json, log);
  if (o.sim) {
    SUBFEED_TRY(verify_dry_run(link, {files.cl, files.nc}, machine, tolerance, log));
  }
  return {};
}

} // namespace

void add_run_command(CLI::App& app, Action& chosen) {
  auto o = std::make_shared<JobRecord>();
  CLI::App* cmd = app.add_subcommand(
      "run", "Plan, post and drip-feed one job, lazily: cutting starts while planning goes on");
  cmd->add_option("cage", o->cage,
                  "Control cage (Wavefront OBJ; units and orientation: --units, --up) to plan, or "
                  "CL data (.cl) to post as it is")
      ->required()
      ->type_name("CAGE.obj|PART.cl");
  add_run_flags(*cmd, *o);
  auto* link = cmd->add_option_group("link", "Where the controller is (exactly one)");
  link->add_option("--port", o->port, "Serial port (any tty path, ptys included)")
      ->type_name("DEV");
  link->add_option("--tcp", o->tcp, "TCP stream (grblHAL Ethernet, serial-to-TCP server)")
      ->type_name("HOST:PORT");
  link->add_flag("--sim", o->sim,
                 "Dry run: the simulated controller that matches the machine, on a pty");
  link->require_option(1);
  cmd->add_option("--sim-speed", o->sim_speed,
                  "With --sim: run the machine N times faster than real time")
      ->check(positive_number());
  cmd->add_option("--sim-baud", o->sim_baud,
                  "With --sim: emulated wire speed (0 = unlimited; DNC: 115200)")
      ->check(CLI::Range(0, 4000000));
  cmd->add_flag("--json", o->json, "Events as JSON, one per line, on stdout");
  cmd->callback([&chosen, o] { chosen = [o](Logger& log) { return run_job(*o, log); }; });
}

} // namespace subfeed::cli
