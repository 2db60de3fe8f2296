// `subfeed check PART.nc --machine M.toml [--cl PART.cl]`: replays a program through the
// machine's forward kinematics and reports what the tool tip does (post/program_check.hpp).
// Exit 2 when anything exceeds the tolerances or the machine's limits.

#include "command.hpp"
#include "setup_flags.hpp"

#include "cl/cl_reader.hpp"
#include "post/machine_config.hpp"
#include "post/program_check.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

namespace subfeed::cli {

namespace {

struct CheckCommandOptions {
  std::string program;
  std::string machine;
  std::string cl;
  double tolerance = 0.002;
  double axis_tolerance = 0.05;
  int samples = 8;
  job::SetupFlags setup;
};

std::string at(const post::Finding& f) {
  return f.line > 0 ? fmt::format(" (line {})", f.line) : "";
}

Expected<void> run_check(const CheckCommandOptions& o, Logger& log) {
  SUBFEED_TRY_ASSIGN(const auto machine, post::load_machine_config(o.machine));
  post::CheckOptions options;
  options.tolerance = o.tolerance;
  options.axis_tolerance = o.axis_tolerance;
  options.samples_per_block = o.samples;
  if (!o.cl.empty()) {
    options.cl = o.cl;
    SUBFEED_TRY_ASSIGN(const auto reader, cl::ClReader::open(o.cl));
    SUBFEED_TRY(job::agreed_setup(o.setup, reader.header().setup, o.cl));
  } else if (o.setup.any()) {
    return fail(ErrorCode::usage,
                "a setup is checked against the CL data's own record: give --cl as well",
                {{}, 0, "--cl"});
  }
  SUBFEED_TRY_ASSIGN(const auto r, post::check_program(o.program, machine, options));
  log.info(fmt::format("{}: {} lines, {} motion blocks, {} feed blocks, cutting time {:.2f} min",
                       o.program, r.lines, r.motion_blocks, r.feed_blocks, r.cutting_minutes));
  if (options.cl) {
    log.info(fmt::format("  against {}: {} cutting blocks, tool tip deviation max {:.6f} mm{} "
                         "(tolerance {} mm), tool axis deviation max {:.4f} deg{} (allowed {:.4f})",
                         o.cl, r.cut_blocks_compared, r.tip_deviation.value, at(r.tip_deviation),
                         o.tolerance, r.axis_deviation.value, at(r.axis_deviation),
                         r.allowed_axis_deviation));
  }
  log.info(
      fmt::format("  tool tip feed max {:.1f} mm/min{}", r.max_tip_feed.value, at(r.max_tip_feed)));
  log.info(fmt::format("  limit violations {}{}, rotary jumps over 180 deg {}{}, blocks over an "
                       "axis max feed {}{}",
                       r.limit_violations, at(r.first_limit_violation), r.rotary_jumps,
                       at(r.first_rotary_jump), r.over_feed, at(r.first_over_feed)));
  if (!r.passed(o.tolerance)) {
    return fail(ErrorCode::bad_input, "check failed: see the report above", {o.program, 0, {}});
  }
  log.info("  check passed");
  return {};
}

} // namespace

void add_check_command(CLI::App& app, Action& chosen) {
  auto o = std::make_shared<CheckCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "check", "Replay G-code through the machine's kinematics: tip deviation, limits, feeds");
  cmd->add_option("program", o->program, "G-code program")->required()->type_name("PART.nc");
  cmd->add_option("--machine", o->machine, "Machine config")->required()->type_name("M.toml");
  cmd->add_option("--cl", o->cl, "CL data the program was posted from (needs PART.nc.map)")
      ->type_name("PART.cl");
  cmd->add_option("--tolerance", o->tolerance, "Tool tip deviation allowed, mm")
      ->check(CLI::Range(1e-6, 10.0));
  cmd->add_option("--axis-tolerance", o->axis_tolerance, "Tool axis deviation allowed, deg")
      ->check(CLI::Range(1e-5, 10.0));
  cmd->add_option("--samples", o->samples, "Points checked inside every feed block")
      ->check(CLI::Range(1, 1000));
  add_setup_flags(*cmd, o->setup);
  cmd->callback([&chosen, o] { chosen = [o](Logger& log) { return run_check(*o, log); }; });
}

} // namespace subfeed::cli
