#pragma once
// Where the planner lifted CL points clear of the part: the ball set on its contact point
// along the normal would have cut in elsewhere (the other wall of a hollow or a concave
// edge narrower than the ball), so it was raised until clear and leaves up to that much
// material on the contact point. Points within `link` mm of each other form one region, so
// that a user is told where and how much, thickest first.

#include <Eigen/Core>
#include <vector>

namespace subfeed::geometry {

struct LiftedPoint {
  Eigen::Vector3d contact = Eigen::Vector3d::Zero(); // mm, where the ball should have touched
  double lift_mm = 0.0;                              // how far it was raised
};

struct LiftedRegion {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero(); // mm, the mean of its contacts
  Eigen::Vector3d low = Eigen::Vector3d::Zero();      // bounding box of the contacts, mm
  Eigen::Vector3d high = Eigen::Vector3d::Zero();
  long points = 0;
  double max_lift_mm = 0.0; // the most material left there
};

// Regions of the points joined when they lie in the same or neighbouring cells of a grid
// of `link` mm (so within 2 sqrt(3) link at most, and always within link): thickest first.
[[nodiscard]] std::vector<LiftedRegion> lifted_regions(const std::vector<LiftedPoint>& points,
                                                       double link);

} // namespace subfeed::geometry
