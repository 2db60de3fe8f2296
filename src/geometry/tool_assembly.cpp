#include "geometry/tool_assembly.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace subfeed::geometry {

namespace {

// The distance in the (along, across) plane from (x, y) to the segment ab.
double section_segment_distance(double x, double y, double ax, double ay, double bx, double by) {
  const double dx = bx - ax, dy = by - ay;
  const double length2 = dx * dx + dy * dy;
  const double t =
      length2 > 0.0 ? std::clamp(((x - ax) * dx + (y - ay) * dy) / length2, 0.0, 1.0) : 0.0;
  const double ex = x - (ax + t * dx), ey = y - (ay + t * dy);
  return std::sqrt(ex * ex + ey * ey);
}

} // namespace

ToolAssembly ToolAssembly::ball_only(double ball_radius) {
  const double d = 2.0 * ball_radius;
  return {.ball_radius = ball_radius,
          .flute_length = 3.0 * d,
          .shank_diameter = d,
          .stickout = 4.0 * d,
          .holder = {},
          .defaulted = true};
}

Expected<void> ToolAssembly::validate(const std::string& what) const {
  const auto bad = [&](const std::string& message) {
    return fail(ErrorCode::usage, message, {{}, 0, what});
  };
  if (!(ball_radius > 0.0)) {
    return bad("the cutter's diameter must be more than 0");
  }
  if (!(flute_length >= ball_radius)) {
    return bad(fmt::format("the flute length ({:g} mm) must reach at least the ball's centre "
                           "({:g} mm)",
                           flute_length, ball_radius));
  }
  if (!(shank_diameter > 0.0)) {
    return bad("the shank diameter must be more than 0");
  }
  if (!(stickout >= flute_length)) {
    return bad(fmt::format("the stick-out ({:g} mm) must be at least the flute length ({:g} mm)",
                           stickout, flute_length));
  }
  for (std::size_t i = 0; i < holder.size(); ++i) {
    const auto& h = holder[i];
    if (!(h.bottom_diameter > 0.0) || !(h.top_diameter > 0.0) || !(h.length > 0.0)) {
      return bad(fmt::format("holder stage {}: diameters and length must be more than 0", i + 1));
    }
  }
  return {};
}

std::vector<ToolBody> ToolAssembly::bodies() const {
  const double r = ball_radius;
  std::vector<ToolBody> out;
  if (flute_length > r) {
    out.push_back({"flutes", r, flute_length, r, r, true});
  }
  if (stickout > flute_length) {
    const double s = shank_diameter / 2.0;
    out.push_back({"shank", flute_length, stickout, s, s, false});
  }
  double at = stickout;
  for (std::size_t i = 0; i < holder.size(); ++i) {
    const auto& h = holder[i];
    out.push_back({fmt::format("holder {}", i + 1), at, at + h.length, h.bottom_diameter / 2.0,
                   h.top_diameter / 2.0, false});
    at += h.length;
  }
  return out;
}

double ToolAssembly::length() const {
  double top = std::max(stickout, flute_length);
  for (const auto& h : holder) {
    top += h.length;
  }
  return top;
}

std::string HolderStage::text() const {
  return bottom_diameter == top_diameter
             ? fmt::format("{:g}:{:g}", bottom_diameter, length)
             : fmt::format("{:g}:{:g}:{:g}", bottom_diameter, top_diameter, length);
}

std::string ToolAssembly::text() const {
  std::string out = fmt::format("ball {:g}, flutes {:g}, shank {:g}, stick-out {:g}, ",
                                2.0 * ball_radius, flute_length, shank_diameter, stickout);
  if (holder.empty()) {
    out += "no holder";
  } else {
    out += "holder";
    for (const auto& h : holder) {
      out += " " + h.text();
    }
  }
  return out;
}

double body_distance(const ToolBody& body, const Eigen::Vector3d& tip, const Eigen::Vector3d& axis,
                     const Eigen::Vector3d& p) {
  const Eigen::Vector3d d = p - tip;
  const double along = d.dot(axis);
  const double across = std::sqrt(std::max(0.0, d.squaredNorm() - along * along));
  const double length = body.to_mm - body.from_mm;
  if (along >= body.from_mm && along <= body.to_mm) {
    const double t = length > 0.0 ? (along - body.from_mm) / length : 0.0;
    if (across <= body.radius_from_mm + t * (body.radius_to_mm - body.radius_from_mm)) {
      return 0.0;
    }
  }
  // Outside: the nearest of the three edges of the body's half-section (the axis is inside).
  return std::min(
      {section_segment_distance(along, across, body.from_mm, 0.0, body.from_mm,
                                body.radius_from_mm),
       section_segment_distance(along, across, body.to_mm, 0.0, body.to_mm, body.radius_to_mm),
       section_segment_distance(along, across, body.from_mm, body.radius_from_mm, body.to_mm,
                                body.radius_to_mm)});
}

Eigen::Vector3d body_lowest_point(const ToolBody& body, const Eigen::Vector3d& tip,
                                  const Eigen::Vector3d& axis) {
  // A circle about the axis reaches lowest where it meets the vertical plane through the
  // axis, on the side of -Z; a level circle (a vertical axis) anywhere: its centre's foot.
  Eigen::Vector3d down = -Eigen::Vector3d::UnitZ() + axis.z() * axis;
  down = down.norm() > 1e-12 ? Eigen::Vector3d(down.normalized()) : Eigen::Vector3d::Zero();
  const Eigen::Vector3d from = tip + body.from_mm * axis + body.radius_from_mm * down;
  const Eigen::Vector3d to = tip + body.to_mm * axis + body.radius_to_mm * down;
  return from.z() <= to.z() ? from : to;
}

double body_lowest_z(const ToolBody& body, const Eigen::Vector3d& tip,
                     const Eigen::Vector3d& axis) {
  return body_lowest_point(body, tip, axis).z();
}

} // namespace subfeed::geometry
