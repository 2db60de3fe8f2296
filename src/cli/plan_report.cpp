#include "plan_report.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace subfeed::cli {

namespace {

// Rounded to the hundredth shown, and never "-0.00".
double shown_mm(double v) {
  return std::round(v * 100.0) / 100.0 + 0.0;
}

} // namespace

namespace {

// One place where material thicker than H is left, from a hollow or from lifted CL points.
struct LeftPlace {
  Eigen::Vector3d centre, low, high;
  double material_mm = 0.0;
  long vertices = 0;      // of the surface, in a hollow narrower than the ball
  long lifted_points = 0; // CL points raised clear of the part there
};

bool near_box(const Eigen::Vector3d& p, const LeftPlace& place, double margin) {
  return (p.array() >= place.low.array() - margin).all() &&
         (p.array() <= place.high.array() + margin).all();
}

// Hollows first, then the lifted points no hollow explains; thickest first.
std::vector<LeftPlace> places_left(const geometry::PlanSummary& s) {
  std::vector<LeftPlace> places;
  for (const auto& r : s.unreachable_regions) {
    if (r.material_mm > s.scallop) {
      places.push_back({r.centroid, r.low, r.high, r.material_mm, r.vertices, 0});
    }
  }
  const std::size_t hollows = places.size();
  for (const auto& r : s.lifted_regions) {
    if (r.max_lift_mm <= s.scallop) {
      continue;
    }
    const auto it =
        std::find_if(places.begin(), places.begin() + static_cast<long>(hollows),
                     [&](const LeftPlace& p) { return near_box(r.centroid, p, s.ball_radius); });
    if (it != places.begin() + static_cast<long>(hollows)) {
      it->lifted_points += r.points;
      it->material_mm = std::max(it->material_mm, r.max_lift_mm);
    } else {
      places.push_back({r.centroid, r.low, r.high, r.max_lift_mm, 0, r.points});
    }
  }
  std::ranges::stable_sort(places, std::greater{}, &LeftPlace::material_mm);
  return places;
}

std::string describe(const LeftPlace& p) {
  const Eigen::Vector3d size = p.high - p.low;
  std::string why =
      p.vertices > 0 ? fmt::format("a hollow narrower than the ball ({} surface "
                                   "vertices{})",
                                   p.vertices,
                                   p.lifted_points > 0
                                       ? fmt::format(", {} CL points lifted clear", p.lifted_points)
                                       : "")
                     : fmt::format("{} CL points lifted clear of the part (set on the "
                                   "surface there, the ball would cut into it nearby)",
                                   p.lifted_points);
  return fmt::format("    near ({:.2f}, {:.2f}, {:.2f}) mm, over {:.2f} x {:.2f} x {:.2f} mm: up "
                     "to {:.3f} mm, {}",
                     shown_mm(p.centre.x()), shown_mm(p.centre.y()), shown_mm(p.centre.z()),
                     size.x(), size.y(), size.z(), p.material_mm, why);
}

// What stays under H, said once: true, and nothing to act on.
std::string thinner_note(const geometry::PlanSummary& s) {
  double hollow = 0.0, lift = 0.0;
  long vertices = 0;
  for (const auto& r : s.unreachable_regions) {
    if (r.material_mm <= s.scallop) {
      hollow = std::max(hollow, r.material_mm);
      vertices += r.vertices;
    }
  }
  long points = 0;
  for (const auto& r : s.lifted_regions) {
    if (r.max_lift_mm <= s.scallop) {
      lift = std::max(lift, r.max_lift_mm);
      points += r.points;
    }
  }
  std::string note;
  if (vertices > 0 && hollow >= 0.5e-4) { // a hollow that keeps nothing shown is noise
    note += fmt::format("; {} surface vertices in hollows narrower than the ball keep at most "
                        "{:.4f} mm",
                        vertices, hollow);
  }
  if (points > 0) {
    note += fmt::format("; {} CL points lifted clear of the part leave at most {:.4f} mm", points,
                        lift);
  }
  return note;
}

} // namespace

std::string time_summary(const geometry::PlanTimes& t, int solves) {
  using geometry::PlanStage;
  std::string text = "  time:";
  for (std::size_t i = 0; i < geometry::plan_stage_count; ++i) {
    const auto stage = static_cast<PlanStage>(i);
    if (stage == PlanStage::directions && t[stage] == 0.0) {
      continue; // no pricing asked for
    }
    text += fmt::format("{} {} {:.2f} s", i == 0 ? "" : ",", geometry::stage_name(stage), t[stage]);
    if (stage == PlanStage::deformation && solves > 0) {
      text += fmt::format(" ({} solves)", solves);
    }
    if (stage == PlanStage::slicing) {
      text += fmt::format(" (motion gate checks {:.2f} s, routing links {:.2f} s, handing poses "
                          "on {:.2f} s)",
                          t.gate_checks_s, t.links_s, t.sink_s);
    }
  }
  return text + fmt::format("; {:.2f} s in all", t.total_s());
}

namespace {

std::string shown_distance(double mm, double searched) {
  return std::isfinite(mm) ? fmt::format("{:.3f} mm", mm) : fmt::format("over {:g} mm", searched);
}

std::string describe(const geometry::ReachRegion& r) {
  const Eigen::Vector3d size = r.high - r.low;
  std::string why;
  if (r.tilted > 0) {
    why = fmt::format("normals up to {:.1f} deg from +Z", r.steepest_deg);
  }
  if (r.hidden > 0) {
    why += fmt::format("{}{} surface vertices hidden under the part", why.empty() ? "" : ", ",
                       r.hidden);
  }
  if (r.collides > 0) {
    why += fmt::format("{}{} where no tool axis keeps the holder, shank and flutes clear",
                       why.empty() ? "" : ", ", r.collides);
  }
  if (r.below_floor > 0) {
    why += fmt::format("{}{} the ball reaches only below the floor", why.empty() ? "" : ", ",
                       r.below_floor);
  }
  return fmt::format("    near ({:.2f}, {:.2f}, {:.2f}) mm, over {:.2f} x {:.2f} x {:.2f} mm: "
                     "{:.1f} mm^2, {}",
                     shown_mm(r.centroid.x()), shown_mm(r.centroid.y()), shown_mm(r.centroid.z()),
                     size.x(), size.y(), size.z(), r.area_mm2, why);
}

} // namespace

void report_out_of_reach(const geometry::PlanSummary& s, Logger& log) {
  const auto& regions = s.out_of_reach;
  if (regions.empty()) {
    log.info(fmt::format("  out of the tool's reach: nothing (every normal within {:g} deg of "
                         "+Z, nothing hidden)",
                         s.reach_angle_deg));
    return;
  }
  double area = 0.0;
  for (const auto& r : regions) {
    area += r.area_mm2;
  }
  log.warning(fmt::format("  left uncut, out of the tool's reach: {:.1f} mm^2 in {} region(s) "
                          "(normals more than {:g} deg from +Z, hidden under the part, no "
                          "clear tool axis, or below the floor)",
                          area, regions.size(), s.reach_angle_deg));
  constexpr std::size_t shown = 8;
  for (std::size_t i = 0; i < std::min(shown, regions.size()); ++i) {
    log.warning(describe(regions[i]));
  }
  if (regions.size() > shown) {
    log.warning(fmt::format("    and {} smaller", regions.size() - shown));
  }
}

void report_left_material(const geometry::PlanSummary& s, Logger& log) {
  report_out_of_reach(s, log);
  const auto places = places_left(s);
  if (places.empty()) {
    log.info(fmt::format("  material left thicker than H ({:g} mm): none{}", s.scallop,
                         thinner_note(s)));
    return;
  }
  const double most = places.front().material_mm;
  log.warning(fmt::format("  material thicker than H ({:g} mm) is left in {} place(s) the ball "
                          "cannot follow, up to {:.3f} mm: finish them with a smaller ball",
                          s.scallop, places.size(), most));
  constexpr std::size_t shown = 8;
  for (std::size_t i = 0; i < std::min(shown, places.size()); ++i) {
    log.warning(describe(places[i]));
  }
  if (places.size() > shown) {
    log.warning(fmt::format("    and {} thinner", places.size() - shown));
  }
}

std::string tool_summary(const geometry::ToolAssembly& tool, const geometry::PlanSummary& s) {
  const auto& f = s.fixture;
  const auto& c = s.clear_axes;
  std::string text = fmt::format(
      "  tool: {}{}; floor {}, stock {:g} mm below it, clearance {:g} mm", tool.text(),
      tool.defaulted ? " (defaults: flutes 3D, shank D, stick-out 4D; give --flute, --shank, "
                       "--stickout, --holder for the real tool)"
                     : "",
      f.floor_z ? fmt::format("z {:.3f} mm", *f.floor_z) : std::string("none"), f.stock_margin,
      f.clearance_min);
  if (c.turned > 0 || c.collided > 0) {
    text += fmt::format("; tool axis turned clear at {} vertices (up to {:.1f} deg, ramped over "
                        "{} more), {} left uncut with no clear axis",
                        c.turned, c.largest_turn_deg, c.spread, c.collided);
  }
  return text;
}

std::string axis_summary(const geometry::PlanOptions& options, const geometry::PlanSummary& s) {
  if (options.fixed_axis) {
    return {};
  }
  const auto& a = s.axis_steps;
  std::string text =
      fmt::format("  tool axis along passes: turns {:.2f} deg between poses on "
                  "average, at most {:.2f} deg (near ({:.2f}, {:.2f}, {:.2f}) mm)",
                  a.mean_deg, a.largest_deg, a.largest_at.x(), a.largest_at.y(), a.largest_at.z());
  const auto& l = s.lean;
  if (options.lean.any() && l.points > 0) {
    text +=
        fmt::format("; lead {:g} deg, tilt {:g} deg kept in full at {:.1f} % of {} points",
                    options.lean.lead_deg, options.lean.tilt_deg,
                    100.0 * static_cast<double>(l.full) / static_cast<double>(l.points), l.points);
    if (l.reduced > 0) {
      text += fmt::format(", eased toward the unleaned axis at {} (down to {:.0f} %) where the "
                          "full lean would collide, pass the tilt limit or cut off the ball",
                          l.reduced, 100.0 * l.least_fraction);
    }
  }
  return text;
}

std::string posted_gate_summary(const geometry::GateReport& gate) {
  std::string text = fmt::format("  posted program: {} poses ({} in rapids) as the machine moves "
                                 "its joints checked against the part: no cut deeper than {:g} "
                                 "um, no rapid touching it",
                                 gate.moves, gate.rapids, gate.tolerance * 1000.0);
  if (!gate.clearance.empty()) {
    text += "; the whole tool kept its clearance and stayed above the floor";
  }
  return text;
}

std::string gate_summary(const geometry::GateReport& gate) {
  if (!gate.clearance.empty()) {
    const double searched = gate.clearance_searched;
    std::string bodies;
    for (const auto& b : gate.clearance) {
      bodies += fmt::format("{}{} ", bodies.empty() ? "" : "; ", b.body);
      bodies += b.body == "ball"
                    ? ""
                    : fmt::format("{} from the part, ", shown_distance(b.to_part, searched));
      bodies += std::isfinite(b.to_floor) ? fmt::format("{:.3f} mm above the floor", b.to_floor)
                                          : std::string("no floor");
    }
    return fmt::format("  motion gate: {} moves ({} rapids) checked against the part (its limit "
                       "surface itself): no cut deeper than {:g} um, no rapid touching it; least "
                       "clearance: {}",
                       gate.moves, gate.rapids, gate.tolerance * 1000.0, bodies);
  }
  return fmt::format("  motion gate: {} moves ({} rapids) checked against the part (its limit "
                     "surface itself): no cut deeper than {:g} um, no rapid touching it",
                     gate.moves, gate.rapids, gate.tolerance * 1000.0);
}

} // namespace subfeed::cli
