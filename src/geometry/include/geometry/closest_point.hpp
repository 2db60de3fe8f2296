#pragma once
// The points of a segment and of a triangle nearest to a point in space. The triangle's (Voronoi
// regions of vertices, edges and face, as in Ericson, Real-Time Collision Detection, 5.1.5). A
// degenerate triangle's answer is the nearest point of its edges where the regions decide it, else
// its first vertex.

#include <Eigen/Core>

namespace subfeed::geometry {

// A zero-length segment answers its one point.
[[nodiscard]] Eigen::Vector3d closest_on_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                                 const Eigen::Vector3d& b);

[[nodiscard]] Eigen::Vector3d closest_on_triangle(const Eigen::Vector3d& p,
                                                  const Eigen::Vector3d& a,
                                                  const Eigen::Vector3d& b,
                                                  const Eigen::Vector3d& c);

// The nearest pair of points of a segment and a triangle: `on_segment` and `on_triangle`;
// where the segment pierces the triangle both are the piercing point.
struct SegmentTriangleNearest {
  Eigen::Vector3d on_segment, on_triangle;
  [[nodiscard]] double distance() const { return (on_segment - on_triangle).norm(); }
};
[[nodiscard]] SegmentTriangleNearest closest_segment_triangle(const Eigen::Vector3d& p,
                                                              const Eigen::Vector3d& q,
                                                              const Eigen::Vector3d& a,
                                                              const Eigen::Vector3d& b,
                                                              const Eigen::Vector3d& c);

} // namespace subfeed::geometry
