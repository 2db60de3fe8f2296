#pragma once
// The sum of vectors attached to points, over the points within a ball: a box tree whose
// nodes keep their points' sum, so a node wholly inside the ball adds its sum at once and
// only nodes the sphere cuts are opened. The same sum as adding every point within the ball
// one by one (to rounding), at a cost that grows with the sphere's rim, not its inside: the
// tool axis, the area-weighted normals of the triangles within a radius, at every vertex.

#include <Eigen/Core>
#include <vector>

namespace subfeed::geometry {

class VectorSumTree {
public:
  // `points` and `vectors` pair up; both are copied.
  VectorSumTree(const std::vector<Eigen::Vector3d>& points,
                const std::vector<Eigen::Vector3d>& vectors);

  // The sum of vectors[i] over the points i within `radius` of `p` (mm), boundary included.
  [[nodiscard]] Eigen::Vector3d sum_within(const Eigen::Vector3d& p, double radius) const;

private:
  struct Node {
    Eigen::Vector3d low, high, sum;
    int first = 0, count = 0;
    int left = -1, right = -1; // -1: a leaf
  };
  int build(int first, int count);

  std::vector<Eigen::Vector3d> points_, vectors_; // in tree order
  std::vector<Node> nodes_;
};

} // namespace subfeed::geometry
