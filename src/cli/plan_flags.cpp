#include "plan_flags.hpp"

#include "job/logger.hpp"
#include "job/tool_spec.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

namespace subfeed::cli {

using namespace subfeed::job; // NOLINT: the front wires the job library

void add_tool_flags(CLI::App& cmd, job::PlanSettings& o, bool required) {
  cmd.add_option("--tool", o.tool,
                 "Cutter: ball:D (diameter D mm), or a tool's name in the tool table (with its "
                 "flutes, shank, stick-out and holder; flags given here win)")
      ->required(required)
      ->type_name("ball:D|NAME");
  cmd.add_option("--tools", o.tool_table,
                 "Tool table that --tool NAME is looked up in (default configs/tools.toml)")
      ->type_name("FILE");
  cmd.add_option("--flute", o.flute, "Flute length from the tip, mm (default 3 D)")
      ->type_name("MM")
      ->check(CLI::Range(1e-3, 10000.0));
  cmd.add_option("--shank", o.shank, "Shank diameter, mm (default the cutter's)")
      ->type_name("MM")
      ->check(CLI::Range(1e-3, 10000.0));
  cmd.add_option("--stickout", o.stickout,
                 "From the tip to the holder's face, mm (default 4 D, at least the flutes)")
      ->type_name("MM")
      ->check(CLI::Range(1e-3, 10000.0));
  cmd.add_option("--holder", o.holder,
                 "A holder stage, D:L (cylinder) or D1:D2:L (cone, D1 nearer the tip), mm; repeat "
                 "for a stack, bottom first (default: no holder)")
      ->type_name("D:L")
      ->take_all();
  cmd.add_option("--floor", o.floor,
                 "Table or fixture top, z in the part's frame (mm), or none (default: the part's "
                 "lowest point); nothing of the tool may go below it")
      ->type_name("Z|none");
  cmd.add_option("--stock-margin", o.stock_margin,
                 "How far below the floor the stock reaches, mm: the ball and flutes may cut that "
                 "deep (default 0)")
      ->type_name("MM")
      ->check(CLI::Range(0.0, 10000.0));
  cmd.add_option("--clearance-min", o.clearance_min,
                 "Least distance every part of the tool but the ball keeps from the part, mm "
                 "(default 0.5)")
      ->type_name("MM")
      ->check(CLI::Range(0.0, 100.0));
}

void add_plan_flags(CLI::App& cmd, job::PlanSettings& o, bool required) {
  add_tool_flags(cmd, o, required);
  cmd.add_option("--scallop", o.scallop, "Scallop height target, mm")->required(required);
  cmd.add_option(
      "--direction", o.direction,
      "Feed direction: x, y, degrees from X, concentric (rings about the highest point) or auto "
      "(the shortest predicted path, rings included); default x, but rings where parallel "
      "passes would cut over twice the ideal length and rings are shorter (walls facing the "
      "planes: a body of revolution, a box)");
  cmd.add_flag("--baseline", o.baseline, "Constant-interval iso-planar passes for comparison");
  cmd.add_option("--axis-radius", o.axis_radius,
                 "Tool axis averaging radius zeta, mm (default: ball radius)")
      ->check(CLI::Range(1e-3, 1000.0));
  cmd.add_option("--axis", o.axis, "Tool axis: normal (five axes) or fixed (vertical, three axes)")
      ->check(CLI::IsMember({"normal", "fixed"}));
  cmd.add_option("--max-tilt", o.max_tilt,
                 "Largest tool tilt from vertical, degrees: steeper surface, and surface hidden "
                 "under the part, is left uncut and reported (default: the machine's tilt range "
                 "with --machine, else 90)")
      ->type_name("DEG")
      ->check(CLI::Range(0.0, 180.0));
  cmd.add_option("--lead", o.lead,
                 "Lean the tool's top this far ahead of the feed direction (negative: behind), "
                 "degrees, so a ball-end does not cut with its tip; less where the full lean "
                 "would collide or exceed the tilt (default 0)")
      ->type_name("DEG")
      ->check(CLI::Range(-45.0, 45.0));
  cmd.add_option("--tilt", o.tilt,
                 "Lean the tool's top this far to the left of the feed direction (negative: "
                 "right), degrees (default 0)")
      ->type_name("DEG")
      ->check(CLI::Range(-45.0, 45.0));
  cmd.add_flag("--one-way", o.one_way, "Cut every pass in the same direction (default zig-zag)");
  cmd.add_option("--feed", o.feed, "Cutting feed, mm/min")->check(CLI::Range(1.0, 100000.0));
  cmd.add_option("--plunge-feed", o.plunge_feed, "Plunge feed, mm/min")
      ->check(CLI::Range(1.0, 100000.0));
  cmd.add_option("--clearance", o.clearance, "Retract along the tool axis between passes, mm")
      ->check(CLI::Range(0.01, 1000.0));
  cmd.add_option("--stay-down", o.stay_down,
                 "Reach a pass starting within MM by feed along the surface where the ball "
                 "clears it (default the ball's diameter; 0: always retract)")
      ->type_name("MM")
      ->check(CLI::Range(0.0, 1000.0));
  cmd.add_option("--tolerance", o.tolerance,
                 "Chordal tolerance along the passes, mm (default min(H/10, 0.0004))")
      ->check(CLI::Range(1e-6, 1.0));
  cmd.add_option("--mesh-chord", o.mesh_chord,
                 "Chord of the planner's mesh of the surface, where the passes are sliced; "
                 "the poses are placed on the surface itself, mm (default min(H/4, 0.002); rings and "
                 "--direction auto: --tolerance)")
      ->type_name("MM")
      ->check(CLI::Range(1e-6, 1.0));
  add_gate_tolerance_flag(cmd, o.gate_tolerance);
  cmd.add_option("--level", o.level, "Bfr approximation level near irregular features")
      ->check(CLI::Range(geometry::min_approx_level, geometry::max_approx_level));
  cmd.add_option("--refine", o.refine,
                 "Most deformation solves while measured spacing exceeds the need")
      ->check(CLI::Range(1, 100));
}

Expected<void> resolve_tool(job::PlanSettings& settings, job::Logger& log) {
  const std::string name = settings.tool;
  SUBFEED_TRY_ASSIGN(const auto from, job::resolve_tool_name(settings));
  if (from) {
    std::string flags = "--tool " + settings.tool;
    const auto add = [&flags](const char* flag, double mm) {
      flags += mm > 0.0 ? fmt::format(" {} {:g}", flag, mm) : std::string();
    };
    add("--flute", settings.flute);
    add("--shank", settings.shank);
    add("--stickout", settings.stickout);
    for (const auto& h : settings.holder) {
      flags += " --holder " + h;
    }
    log.info(fmt::format("tool {} ({}): {}", name, *from, flags));
  }
  return {};
}

void add_gate_tolerance_flag(CLI::App& cmd, double& tolerance_mm) {
  cmd.add_option("--gate-tolerance", tolerance_mm,
                 "Deepest cut below the surface the motion gate lets through, mm (default "
                 "0.001; when planning, 2.5 times --tolerance where that is more); rapids may "
                 "not touch the part at all")
      ->type_name("MM")
      ->check(CLI::Range(1e-5, 1.0));
}

} // namespace subfeed::cli
