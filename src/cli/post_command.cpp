// `subfeed post PART.cl --machine M.toml [--dialect grbl|fanuc|linuxcnc] -o PART.nc`: CL
// data to G-code for one machine (postprocessors/post_file.hpp).

#include "command.hpp"
#include "job/block_gate.hpp"
#include "job/cl_gate.hpp"
#include "plan_flags.hpp"
#include "plan_report.hpp"
#include "setup_flags.hpp"

#include "cl/cl_reader.hpp"
#include "geometry/limit_surface.hpp"
#include "post/machine_config.hpp"
#include "post/post_file.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <map>

namespace subfeed::cli {

using namespace subfeed::job; // NOLINT: the front wires the job library

namespace {

struct PostCommandOptions {
  std::string cl;
  std::string machine;
  std::string output;
  std::string dialect;
  std::string tcp = "off";
  double tolerance = 0.002;
  double axis_tolerance = 0.05;
  bool comments = false;
  bool line_numbers = false;
  bool no_look_ahead = false;
  double spindle = 0.0;
  std::string cage; // check every move against its part first
  SetupFlags setup;
  double gate_tolerance = 0.0; // mm; 0: the gate's default
  int level = geometry::min_approx_level;
};

Expected<void> run_post(const PostCommandOptions& o, Logger& log) {
  SUBFEED_TRY_ASSIGN(const auto machine, post::load_machine_config(o.machine));
  post::PostFileOptions options;
  options.program = post::program_options_for(machine);
  if (!o.dialect.empty()) {
    options.program.dialect = o.dialect == "grbl"    ? post::Dialect::grbl
                              : o.dialect == "fanuc" ? post::Dialect::fanuc
                                                     : post::Dialect::linuxcnc;
  }
  options.program.comments = o.comments || options.program.dialect == post::Dialect::linuxcnc;
  options.program.line_numbers = o.line_numbers;
  options.program.blend_tolerance = o.tolerance;
  if (o.spindle > 0.0) {
    options.program.spindle_rpm = o.spindle;
  }
  options.post.tolerance = o.tolerance;
  options.post.axis_tolerance = o.axis_tolerance;
  options.post.tcp = o.tcp == "angles"   ? post::TcpMode::angles
                     : o.tcp == "vector" ? post::TcpMode::vector
                                         : post::TcpMode::off;
  if (options.post.tcp != post::TcpMode::off && options.program.dialect == post::Dialect::grbl) {
    return fail(ErrorCode::usage, "the grbl dialect has no tool-centre-point control",
                {{}, 0, "--tcp"});
  }
  options.look_ahead = !o.no_look_ahead;
  std::optional<geometry::MotionGate> gate;
  std::optional<BlockGate> blocks;
  if (!o.cage.empty()) {
    SUBFEED_TRY_ASSIGN(const auto reader, cl::ClReader::open(o.cl));
    SUBFEED_TRY_ASSIGN(
        auto built, gate_for_cl(o.cage, reader.header(), o.cl, o.setup, o.level, o.gate_tolerance));
    gate.emplace(std::move(built));
    options.check = [&gate](const cl::ClPose& pose) { return gate->check(pose); };
    // What the machine will do: every block, the post's own moves too.
    blocks.emplace(machine, gate->sibling(gate->options().tolerance + options.post.tolerance));
    options.check_block = [&blocks](const post::MotionBlock& b) { return blocks->check(b); };
  } else if (o.setup.any()) { // nothing to set up, but a setup said must be the CL's own
    SUBFEED_TRY_ASSIGN(const auto reader, cl::ClReader::open(o.cl));
    SUBFEED_TRY(agreed_setup(o.setup, reader.header().setup, o.cl));
  }
  const std::string output =
      o.output.empty() ? std::filesystem::path(o.cl).replace_extension(".nc").string() : o.output;
  SUBFEED_TRY_ASSIGN(const auto summary, post::post_file(o.cl, machine, options, output));
  const auto& s = summary.stats;
  log.info(fmt::format("{}: {} poses -> {} lines ({} blocks, {} from splitting to {} mm / {} deg), "
                       "{} repositionings, {} poses with C held near the pole (axis within {:.4f} "
                       "deg); trace in {}",
                       output, s.poses, summary.lines, s.blocks, s.splits, o.tolerance,
                       o.axis_tolerance, s.repositions, s.cone_poses, s.max_axis_hold,
                       post::map_path_for(output).string()));
  if (gate) {
    log.info(gate_summary(gate->report()));
    log.info(posted_gate_summary(blocks->report()));
  }
  return {};
}

} // namespace

void add_post_command(CLI::App& app, Action& chosen) {
  auto o = std::make_shared<PostCommandOptions>();
  CLI::App* cmd = app.add_subcommand("post", "Post-process CL data into G-code for one machine");
  cmd->add_option("cl", o->cl, "CL data (APT text)")->required()->type_name("PART.cl");
  cmd->add_option("--machine", o->machine, "Machine config")->required()->type_name("M.toml");
  cmd->add_option("-o,--output", o->output, "G-code to write (default: PART.nc)");
  cmd->add_option("--dialect", o->dialect, "G-code dialect (default: the machine's)")
      ->check(CLI::IsMember({"grbl", "fanuc", "linuxcnc"}));
  cmd->add_option("--tolerance", o->tolerance, "Tool tip deviation allowed between blocks, mm")
      ->check(CLI::Range(1e-5, 1.0));
  cmd->add_option("--axis-tolerance", o->axis_tolerance,
                  "Tool axis deviation allowed between blocks, deg")
      ->check(CLI::Range(1e-4, 5.0));
  cmd->add_option("--tcp", o->tcp, "Tool-centre-point output: off, angles (G43.4), vector (G43.5)")
      ->check(CLI::IsMember({"off", "angles", "vector"}));
  cmd->add_flag("--comments", o->comments, "Write comments (always on for linuxcnc)");
  cmd->add_flag("--line-numbers", o->line_numbers, "Write N numbers (fanuc, linuxcnc)");
  cmd->add_option("--spindle", o->spindle,
                  "Spindle speed, rpm: S and M3 at the start, M5 at the end")
      ->check(CLI::Range(1.0, 200000.0));
  cmd->add_option("--cage", o->cage,
                  "Check every move against the part of this cage first: a cut deeper than "
                  "--gate-tolerance or a rapid touching it is refused and nothing is written")
      ->type_name("CAGE.obj");
  add_gate_tolerance_flag(*cmd, o->gate_tolerance);
  add_setup_flags(*cmd, o->setup);
  cmd->add_option("--level", o->level,
                  "With --cage: Bfr approximation level near irregular features")
      ->check(CLI::Range(geometry::min_approx_level, geometry::max_approx_level));
  cmd->add_flag("--no-look-ahead", o->no_look_ahead,
                "Choose the starting solution from the first pose alone (one pass over the CL)");
  cmd->callback([&chosen, o] { chosen = [o](Logger& log) { return run_post(*o, log); }; });
}

} // namespace subfeed::cli
