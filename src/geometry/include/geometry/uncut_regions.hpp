#pragma once
// Where a path leaves the surface uncut, told as places: samples no ball reached, joined
// into regions where they lie within a link distance of each other, each with its area (the
// samples' shares of the surface), box and centre. `verify` reports them, so what the
// planner left out for reach is measured from the path itself, not taken on its word.

#include <Eigen/Core>
#include <vector>

namespace subfeed::geometry {

struct UncutRegion {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero(); // mm, area-weighted
  Eigen::Vector3d low = Eigen::Vector3d::Zero();      // bounding box, mm
  Eigen::Vector3d high = Eigen::Vector3d::Zero();
  double area_mm2 = 0.0;
  long samples = 0;
};

// `points[i]` stands for `areas[i]` mm^2; samples closer than `link_mm` join. Largest first.
[[nodiscard]] std::vector<UncutRegion> uncut_regions(const std::vector<Eigen::Vector3d>& points,
                                                     const std::vector<double>& areas,
                                                     double link_mm);

} // namespace subfeed::geometry
