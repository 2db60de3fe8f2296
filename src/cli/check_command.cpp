// `subfeed check PART.nc --machine M.toml [--cl PART.cl] [--cage CAGE.obj]`: replays a
// program through the machine's forward kinematics and reports what the tool tip does
// (post/program_check.hpp); with --cage, what the whole tool does too: every pose the joints
// pass through swept against the part and the floor (geometry/path_clearance.hpp). Exit 2
// when anything exceeds the tolerances or the machine's limits, or the tool collides.

#include "clearance_report.hpp"
#include "command.hpp"
#include "plan_flags.hpp"
#include "setup_flags.hpp"

#include "cl/cl_reader.hpp"
#include "geometry/obj_reader.hpp"
#include "geometry/path_clearance.hpp"
#include "job/tool_spec.hpp"
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
  std::string cage;
  job::PlanSettings tool; // the tool and fixture flags, when the CL data records none
};

std::string at(const post::Finding& f) {
  return f.line > 0 ? fmt::format(" (line {})", f.line) : "";
}

// The tool and fixture to check the program with: the CL data's records, else the flags.
Expected<job::RecordedTool> tool_to_check(job::PlanSettings flags, const cl::ClHeader* header,
                                          const std::string& cl_file, bool& floor_at_lowest,
                                          Logger& log) {
  floor_at_lowest = false;
  if (header != nullptr && flags.tool.empty()) {
    SUBFEED_TRY_ASSIGN(const auto recorded, job::recorded_tool(*header, cl_file));
    if (recorded) {
      return *recorded;
    }
  }
  if (flags.tool.empty()) {
    return fail(ErrorCode::usage,
                "the whole tool is needed: give --tool (with --shank, --stickout, --holder), or "
                "--cl with CL data that records it (PPRINT TOOL and FIXTURE)",
                {{}, 0, "--cage"});
  }
  SUBFEED_TRY(resolve_tool(flags, log));
  job::RecordedTool out;
  SUBFEED_TRY_ASSIGN(out.tool, job::tool_assembly_from(flags));
  SUBFEED_TRY_ASSIGN(const auto fixture, job::fixture_from(flags));
  out.fixture = fixture.fixture;
  floor_at_lowest = fixture.floor_at_lowest;
  return out;
}

// The meter that every pose of the replay is swept into, for --cage.
Expected<std::optional<geometry::ClearanceMeter>>
clearance_meter_for(const CheckCommandOptions& o, const cl::ClHeader* header, Logger& log) {
  if (o.cage.empty()) {
    return std::optional<geometry::ClearanceMeter>();
  }
  bool floor_at_lowest = false;
  SUBFEED_TRY_ASSIGN(const auto tool, tool_to_check(o.tool, header, o.cl, floor_at_lowest, log));
  SUBFEED_TRY_ASSIGN(const auto cage,
                     header != nullptr ? job::read_part_agreed(o.cage, o.setup, header->setup, o.cl)
                                       : geometry::read_part(o.cage, o.setup.with_defaults()));
  SUBFEED_TRY_ASSIGN(const auto surface, geometry::LimitSurface::build(cage));
  SUBFEED_TRY_ASSIGN(auto meter, geometry::ClearanceMeter::build(cage, surface, tool.tool,
                                                                 tool.fixture, floor_at_lowest));
  return std::optional<geometry::ClearanceMeter>(std::move(meter));
}

Expected<void> run_check(const CheckCommandOptions& o, Logger& log) {
  SUBFEED_TRY_ASSIGN(const auto machine, post::load_machine_config(o.machine));
  post::CheckOptions options;
  options.tolerance = o.tolerance;
  options.axis_tolerance = o.axis_tolerance;
  options.samples_per_block = o.samples;
  std::optional<cl::ClHeader> header;
  if (!o.cl.empty()) {
    options.cl = o.cl;
    SUBFEED_TRY_ASSIGN(const auto reader, cl::ClReader::open(o.cl));
    SUBFEED_TRY(job::agreed_setup(o.setup, reader.header().setup, o.cl));
    header = reader.header();
  } else if (o.setup.any() && o.cage.empty()) {
    return fail(ErrorCode::usage,
                "a setup is checked against the CL data's own record: give --cl as well",
                {{}, 0, "--cl"});
  }
  SUBFEED_TRY_ASSIGN(auto meter, clearance_meter_for(o, header ? &*header : nullptr, log));
  std::optional<post::ToolPose> last;
  if (meter) {
    options.on_pose = [&](const post::ToolPose& p, long line, bool) {
      const auto& from = last ? *last : p;
      meter->move(Eigen::Vector3d(from.tip.data()), Eigen::Vector3d(from.axis.data()),
                  Eigen::Vector3d(p.tip.data()), Eigen::Vector3d(p.axis.data()), line);
      last = p;
    };
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
  std::string steps;
  for (std::size_t i = 0; i < 3; ++i) {
    if (machine.axes[3 + i]) {
      const auto& f = r.rotary_step[i];
      steps += fmt::format("{}{} {:.3f} deg{}", steps.empty() ? "" : ", ",
                           post::axis_letters[3 + i], f.value, at(f));
    }
  }
  if (!steps.empty()) {
    log.info("  largest rotary step in one feed block: " + steps);
  }
  log.info(fmt::format("  limit violations {}{}, rotary jumps over 180 deg {}{}, blocks over an "
                       "axis max feed {}{}",
                       r.limit_violations, at(r.first_limit_violation), r.rotary_jumps,
                       at(r.first_rotary_jump), r.over_feed, at(r.first_over_feed)));
  if (meter) {
    SUBFEED_TRY(report_clearance(meter->result(), meter->tool(), meter->fixture(), o.program, log));
  }
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
      "check", "Replay G-code through the machine's kinematics: tip deviation, limits, feeds, "
               "and with --cage the whole tool's clearance");
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
  cmd->add_option("--cage", o->cage,
                  "The part's cage: every pose the joints pass through is checked for the whole "
                  "tool's clearance to it and to the floor (the tool from --cl's records, or the "
                  "tool flags)")
      ->type_name("CAGE.obj");
  add_tool_flags(*cmd, o->tool, false);
  add_setup_flags(*cmd, o->setup);
  cmd->callback([&chosen, o] { chosen = [o](Logger& log) { return run_check(*o, log); }; });
}

} // namespace subfeed::cli
