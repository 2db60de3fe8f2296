#pragma once
// How near the tool assembly (tool_assembly.hpp) comes to the part and to the floor, at one
// pose. The ball's own cut is the motion gate's: here the ball counts only against the floor.
//
// Rules (the fixture):
//  - every body above the ball keeps `clearance_min` from the part, the flutes included:
//    only the ball may touch it;
//  - no body comes below the floor, except the ball and the flutes, which may go down to
//    `stock_margin` below it: the stock under the part is there to be cut, the table is not.
//
// Accuracy: the part is the triangle mesh given (the caller's chord from the surface);
// against it, each body's distance is exact at every point measured, and the triangles are
// searched by branch and bound, so a least distance d found is never under the true least
// and at most slop(d) = max(resolution_mm, slop_share (d - clearance_min)) over it: to 10 um
// near the rule, more loosely far from it. Slack is counted from d - slop(d), so it never
// overstates. Floor heights are exact.

#include "geometry/tool_assembly.hpp"
#include "geometry/triangle_tree.hpp"

#include <Eigen/Core>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace subfeed::geometry {

inline constexpr double default_clearance_min = 0.5; // mm

struct Fixture {
  std::optional<double> floor_z;                // mm, the table or fixture top; none: no floor
  double stock_margin = 0.0;                    // mm the stock reaches below the floor
  double clearance_min = default_clearance_min; // mm
};

// One body's least clearance over the poses measured.
struct BodyClearance {
  std::string body; // "ball", "flutes", "shank", "holder 1", ...
  double to_part = std::numeric_limits<double>::infinity();  // mm (the ball: not measured)
  Eigen::Vector3d part_point = Eigen::Vector3d::Zero();      // the part's point nearest it
  double to_floor = std::numeric_limits<double>::infinity(); // mm above the floor; < 0 below
  Eigen::Vector3d floor_tip = Eigen::Vector3d::Zero();       // the tip where it was lowest
};

// What breaks the rules at a pose, for an error.
struct ClearanceViolation {
  std::string body;
  bool floor = false;    // below the floor (or the stock), else too near the part
  double distance = 0.0; // mm from the part, or the depth under the floor's limit
  Eigen::Vector3d where = Eigen::Vector3d::Zero(); // the part's point, or the body's lowest
};

class AssemblyClearance {
public:
  static constexpr double resolution_mm = 0.01;
  static constexpr double slop_share = 0.25;
  static constexpr double floor_tolerance_mm = 1e-3; // a ball resting on the floor is on it

  // `part` (and the points and triangles it indexes) must outlive this.
  AssemblyClearance(const ToolAssembly& tool, const Fixture& fixture, const TriangleTree& part);

  // The first rule the tool at (tip, axis) breaks, with `extra` mm asked beyond
  // clearance_min from the part; nothing when it keeps them all.
  [[nodiscard]] std::optional<ClearanceViolation>
  violation(const Eigen::Vector3d& tip, const Eigen::Vector3d& axis, double extra = 0.0) const;
  [[nodiscard]] bool clear(const Eigen::Vector3d& tip, const Eigen::Vector3d& axis,
                           double extra = 0.0) const {
    return !violation(tip, axis, extra);
  }

  // How far the tool at (tip, axis) is from breaking a rule: the least over the bodies of
  // their distance to the part less clearance_min, and of their height over their floor
  // limit; negative when one is broken (how far is then not searched for: the search ends
  // at the first point under clearance_min). Distances are searched only within `cap` mm of
  // slack (a tool farther off reads `cap`). Each body's clearance is folded into `into` (one per
  // body, the ball first; the least so far is kept), when given.
  [[nodiscard]] double slack(const Eigen::Vector3d& tip, const Eigen::Vector3d& axis, double cap,
                             std::vector<BodyClearance>* into = nullptr) const;
  // Its two halves: the floor's (exact, cheap; infinity without a floor) and the part's.
  [[nodiscard]] double floor_slack(const Eigen::Vector3d& tip, const Eigen::Vector3d& axis,
                                   std::vector<BodyClearance>* into = nullptr) const;
  [[nodiscard]] double part_slack(const Eigen::Vector3d& tip, const Eigen::Vector3d& axis,
                                  double cap, std::vector<BodyClearance>* into = nullptr) const;
  // Entries for slack(), one per body, nothing measured yet.
  [[nodiscard]] std::vector<BodyClearance> blank() const;

  [[nodiscard]] const Fixture& fixture() const { return fixture_; }
  [[nodiscard]] const ToolAssembly& tool() const { return tool_; }
  // How far the farthest point of the assembly lies from the tip, mm: how far a point of it
  // moves when the axis turns by a radian.
  [[nodiscard]] double reach_mm() const { return reach_; }

private:
  // The least distance from the body to the part if under `bound`, with where; any one
  // found under `enough` ends the search (a rule is broken: how far is not asked).
  [[nodiscard]] double to_part(const ToolBody& body, const Eigen::Vector3d& tip,
                               const Eigen::Vector3d& axis, double bound, double enough,
                               Eigen::Vector3d* where) const;
  [[nodiscard]] double slop_at(double distance) const;
  [[nodiscard]] double ball_lowest_z(const Eigen::Vector3d& tip, const Eigen::Vector3d& axis) const;

  ToolAssembly tool_;
  std::vector<ToolBody> bodies_;
  Fixture fixture_;
  const TriangleTree* part_;
  double reach_ = 0.0;
};

} // namespace subfeed::geometry
