#include "job/plan_settings.hpp"

#include "base/number_text.hpp"

#include "job/tool_spec.hpp"

namespace subfeed::job {

namespace {

Expected<double> direction_deg(const std::string& text) {
  if (text == "x") {
    return 0.0;
  }
  if (text == "y") {
    return 90.0;
  }
  if (const auto a = parse_double(text)) {
    return *a;
  }
  return fail(ErrorCode::usage,
              "'" + text + "': expected x, y, auto, concentric or an angle in degrees",
              {{}, 0, "--direction"});
}

} // namespace

Expected<geometry::PlanOptions> plan_options_from(const PlanSettings& o) {
  SUBFEED_TRY_ASSIGN(const double radius, parse_ball_tool(o.tool));
  if (o.scallop <= 0.0 || o.scallop >= radius) {
    return fail(ErrorCode::usage, "must be more than 0 and less than the ball radius",
                {{}, 0, "--scallop"});
  }
  geometry::PlanOptions options;
  options.ball_radius = radius;
  options.scallop = o.scallop;
  options.choose_direction = o.direction == "auto";
  if (o.direction.empty()) {
    options.rings_where_parallel_fails = true; // along x, unless that fights the part
  } else if (o.direction == "concentric") {
    options.pattern = geometry::PassPattern::concentric;
  } else if (!options.choose_direction) {
    SUBFEED_TRY_ASSIGN(options.direction_deg, direction_deg(o.direction));
  }
  options.baseline = o.baseline;
  if (o.axis_radius > 0.0) {
    options.axis_radius = o.axis_radius;
  }
  options.fixed_axis = o.axis == "fixed";
  options.lean.lead_deg = o.lead;
  options.lean.tilt_deg = o.tilt;
  if (options.fixed_axis && options.lean.any()) {
    return fail(ErrorCode::usage, "a vertical tool (--axis fixed) cannot lead or tilt",
                {{}, 0, o.lead != 0.0 ? "--lead" : "--tilt"});
  }
  options.max_tilt_deg = o.max_tilt >= 0.0 ? o.max_tilt : 90.0;
  options.zigzag = !o.one_way;
  options.feed = o.feed;
  options.plunge_feed = o.plunge_feed;
  options.clearance = o.clearance;
  if (o.stay_down >= 0.0) {
    options.stay_down = o.stay_down;
  }
  options.refine_iterations = o.refine;
  if (o.gate_tolerance > 0.0) {
    options.gate_tolerance = o.gate_tolerance;
  }
  if (o.tolerance > 0.0) {
    options.tolerance = o.tolerance;
  }
  if (o.mesh_chord > 0.0) {
    options.mesh_chord = o.mesh_chord;
  }
  if (o.whole_tool) {
    options.whole_tool = true;
    SUBFEED_TRY_ASSIGN(options.tool, tool_assembly_from(o));
    SUBFEED_TRY_ASSIGN(const auto fixture, fixture_from(o));
    options.fixture = fixture.fixture;
    options.floor_at_lowest = fixture.floor_at_lowest;
  }
  return options;
}

} // namespace subfeed::job
